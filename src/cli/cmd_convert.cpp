#include <iostream>

#include "commands.h"
#include "hexdom/io/mesh_io.h"

namespace hexdom::cli {

void add_convert(CLI::App& app) {
  auto* cmd = app.add_subcommand("convert", "Convert a mesh between .k, .vtk, .vtu, .inp, .stl and .obj, or from Gmsh .msh (format by extension)");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto binary = std::make_shared<bool>(false);
  cmd->add_option("-i,--input", *in, "input mesh (.k, .vtk, .vtu, .inp, .msh, .stl, .obj)")->required();
  cmd->add_option("-o,--output", *out, "output mesh (.k, .vtk, .vtu, .inp, .stl, .obj)")->required();
  cmd->add_flag("--binary", *binary, "write legacy VTK in binary");
  cmd->callback([=] {
    io::output_format_of(*out);  // reject an unknown output format before reading
    mesh::Mesh m = io::read_mesh(*in);
    io::WriteOptions opt;
    opt.binary = *binary;
    io::write_mesh(*out, m, opt);
    std::cerr << "hexdom: wrote " << *out << " (" << m.num_nodes() << " nodes, "
              << m.count(mesh::CellType::Hex) << " hex, " << m.count(mesh::CellType::Wedge)
              << " prism, " << m.count(mesh::CellType::Tet) << " tet, "
              << m.count(mesh::CellType::Triangle) + m.count(mesh::CellType::Quad)
              << " surface cells" << (m.second_order() ? ", second order)" : ")") << std::endl;
  });
}

}  // namespace hexdom::cli
