#include "hexdom/cad/read_shape.h"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>
#include <vector>

#include "hexdom/cad/shape_impl.h"
#include "hexdom/io/text.h"

namespace hexdom::cad {

namespace {

const char* kBrepSource = "<BREP string>";

/// Collects OCCT's fail and alarm messages instead of letting them reach stdout.
class CollectingPrinter : public Message_Printer {
 public:
  mutable std::vector<std::string> messages;

 protected:
  void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override {
    if (gravity >= Message_Alarm && messages.size() < 20) messages.emplace_back(text.ToCString());
  }
};

/// While alive, OCCT's default messenger prints to a CollectingPrinter only (the program's stdout
/// stays clean, and in FreeCAD its own printers are put back afterwards). One reader at a time:
/// the messenger and the STEP/IGES sessions are process-wide.
class QuietOcct {
 public:
  QuietOcct() : lock_(mutex()) {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    saved_ = m->Printers();
    m->ChangePrinters().Clear();
    printer_ = new CollectingPrinter;
    m->AddPrinter(printer_);
  }
  ~QuietOcct() { Message::DefaultMessenger()->ChangePrinters() = saved_; }
  /// First collected message, "" when none.
  std::string first() const { return printer_->messages.empty() ? std::string() : printer_->messages.front(); }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  Message_SequenceOfPrinters saved_;
  Handle(CollectingPrinter) printer_;
};

std::string trim_copy(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\n')) ++i;
  return s.substr(i);
}

std::string plural(int n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

int count(const TopoDS_Shape& s, TopAbs_ShapeEnum type) {
  TopTools_IndexedMapOfShape m;
  TopExp::MapShapes(s, type, m);
  return m.Extent();
}

/// Faces of `shape` sewn into shells, each closed shell made a solid (IGES files carry faces).
TopoDS_Shape sew_into_solids(const TopoDS_Shape& shape, const LogCallback& log) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  const double diag = box.IsVoid() ? 1.0 : std::sqrt(box.SquareExtent());
  BRepBuilderAPI_Sewing sewing(1e-6 * diag);
  int nfaces = 0;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next(), ++nfaces) sewing.Add(ex.Current());
  if (nfaces == 0) return shape;
  sewing.Perform();
  TopoDS_Compound out;
  BRep_Builder b;
  b.MakeCompound(out);
  int solids = 0;
  for (TopExp_Explorer ex(sewing.SewedShape(), TopAbs_SHELL); ex.More(); ex.Next()) {
    TopoDS_Shell shell = TopoDS::Shell(ex.Current());
    if (!BRep_Tool::IsClosed(shell)) {
      b.Add(out, shell);
      continue;
    }
    BRepBuilderAPI_MakeSolid make(shell);
    ShapeFix_Solid fix(make.Solid());
    fix.Perform();
    b.Add(out, fix.Solid());
    ++solids;
  }
  if (solids > 0 && log) log(0, "sewed " + plural(nfaces, "face") + " into " + plural(solids, "solid"));
  return solids > 0 ? TopoDS_Shape(out) : shape;
}

/// Checks that the solid's boundary is closed and 2-manifold: every edge other than a degenerated
/// one is used twice by the faces (a seam twice by its one face).
void check_closed(const TopoDS_Shape& solid, const std::string& source, int index) {
  TopTools_IndexedMapOfShape faces, edges;
  TopExp::MapShapes(solid, TopAbs_FACE, faces);
  TopExp::MapShapes(solid, TopAbs_EDGE, edges);
  if (faces.Extent() == 0) throw GeometryError(source + ": solid " + std::to_string(index) + " has no faces");
  std::vector<int> uses(edges.Extent() + 1, 0);
  std::vector<std::vector<int>> face_of(edges.Extent() + 1);
  for (int f = 1; f <= faces.Extent(); ++f)
    for (TopExp_Explorer ex(faces(f), TopAbs_EDGE); ex.More(); ex.Next()) {
      const int e = edges.FindIndex(ex.Current());
      ++uses[e];
      if (face_of[e].empty() || face_of[e].back() != f) face_of[e].push_back(f);
    }
  int open = 0, first_open = 0, nonmanifold = 0, first_nonmanifold = 0;
  for (int e = 1; e <= edges.Extent(); ++e) {
    if (BRep_Tool::Degenerated(TopoDS::Edge(edges(e)))) continue;
    if (uses[e] < 2 && open++ == 0) first_open = e;
    if (uses[e] > 2 && nonmanifold++ == 0) first_nonmanifold = e;
  }
  auto face_list = [&](int e) {
    std::string s;
    for (int f : face_of[e]) s += (s.empty() ? "Face" : ", Face") + std::to_string(f);
    return s;
  };
  const std::string what = source + ": solid " + std::to_string(index);
  if (open > 0)
    throw GeometryError(what + " is open: Edge" + std::to_string(first_open) + " bounds only " +
                        face_list(first_open) + " (" + plural(open, "free edge") + ")");
  if (nonmanifold > 0)
    throw GeometryError(what + " is not 2-manifold: Edge" + std::to_string(first_nonmanifold) +
                        " is shared by " + std::to_string(uses[first_nonmanifold]) + " faces (" +
                        face_list(first_nonmanifold) + ")");
}

/// Picks one solid of `shape` and checks it.
Shape select_solid(const TopoDS_Shape& shape, const std::string& source, const ReadOptions& options) {
  if (shape.IsNull()) throw InputError(source, 0, "holds no geometry");
  TopTools_IndexedMapOfShape solids;
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  const int n = solids.Extent();
  if (n == 0) {
    TopTools_IndexedMapOfShape shells;
    TopExp::MapShapes(shape, TopAbs_SHELL, shells);
    int closed = 0;
    for (int i = 1; i <= shells.Extent(); ++i) closed += BRep_Tool::IsClosed(shells(i)) ? 1 : 0;
    const int nf = count(shape, TopAbs_FACE), ne = count(shape, TopAbs_EDGE);
    std::string what;
    if (shells.Extent() > 0)
      what = "holds no solid but " + plural(shells.Extent(), "shell") + " (" + std::to_string(closed) +
             " closed, " + plural(nf, "face") + "); hexdom meshes solids: make one from a closed shell " +
             "first (FreeCAD: Part > Convert to solid)";
    else if (nf > 0)
      what = "holds no solid, only " + plural(nf, "face") + " not joined into a shell";
    else if (ne > 0)
      what = "holds no solid, only " + plural(ne, "edge") + " (a wireframe)";
    else
      what = "holds no solid (no faces, no edges)";
    throw GeometryError(source + ": " + what);
  }
  int index = options.solid;
  if (index == 0) {
    index = 1;
    if (n > 1 && options.log)
      options.log(1, source + " holds " + std::to_string(n) + " solids; using solid 1 (choose one with --solid N)");
  }
  if (index < 1 || index > n)
    throw InputError(source, 0, "solid " + std::to_string(index) + " requested but there " +
                                    (n == 1 ? "is 1 solid" : "are " + std::to_string(n) + " solids"));
  TopoDS_Shape solid = solids(index);
  check_closed(solid, source, index);
  if (options.log && !BRepCheck_Analyzer(solid).IsValid())
    options.log(1, source + ": solid " + std::to_string(index) + " fails OCCT's validity check; meshing it anyway");
  GProp_GProps props;
  BRepGProp::VolumeProperties(solid, props);
  if (props.Mass() < 0) {
    solid.Reverse();
    if (options.log) options.log(1, source + ": solid " + std::to_string(index) + " was inside out; reversed it");
  }
  return make_shape(solid, source);
}

std::string reader_failure(const std::string& kind, const QuietOcct& quiet) {
  std::string m = trim_copy(quiet.first());
  return "not a readable " + kind + " file" + (m.empty() ? "" : " (" + m + ")");
}

/// The STEP parser's "**** ERR StepFile : ... Line 7: Incorrect syntax: ... ****" as
/// "path:6: Incorrect syntax: ..."; any other failure as "path: not a readable STEP file (...)".
InputError step_failure(const std::string& path, const QuietOcct& quiet) {
  const std::string m = trim_copy(quiet.first());
  std::smatch match;
  static const std::regex line_re(R"(Line (\d+):\s*(.*?)[\s*]*$)");
  // OCCT 7.6's StepFile lexer counts one line too many ("Line 2" for a bad first line, "Line 85"
  // for the end of an 84-line file).
  if (std::regex_search(m, match, line_re))
    return InputError(path, std::max(1L, std::stol(match[1]) - 1), match[2].str());
  return InputError(path, 0, reader_failure("STEP", quiet));
}

}  // namespace

bool is_brep_string(const std::string& text) {
  return text.find("CASCADE Topology") != std::string::npos && text.find('\n') != std::string::npos;
}

namespace {

// The whole shape of a CAD file (IGES faces sewn into solids), before a solid is chosen.
TopoDS_Shape load_file(const std::string& path, const ReadOptions& options) {
  const std::string ext = io::extension(path);
  const bool step = ext == "step" || ext == "stp", iges = ext == "iges" || ext == "igs",
             brep = ext == "brep" || ext == "brp";
  if (!step && !iges && !brep)
    throw InputError(path, 0, "unknown CAD file type '." + ext + "' (expected .step, .stp, .iges, .igs, .brep or .brp)");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw InputError(path, 0, "cannot open file");
    if (std::filesystem::is_directory(path)) throw InputError(path, 0, "is a directory, not a CAD file");
  }
  TopoDS_Shape shape;
  try {
    QuietOcct quiet;
    if (step) {
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) throw step_failure(path, quiet);
      if (reader.TransferRoots() == 0 || reader.NbShapes() == 0)
        throw InputError(path, 0, "STEP file holds no shape that can be transferred" +
                                      (quiet.first().empty() ? std::string() : " (" + trim_copy(quiet.first()) + ")"));
      shape = reader.OneShape();
    } else if (iges) {
      IGESControl_Controller::Init();
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) throw InputError(path, 0, reader_failure("IGES", quiet));
      if (reader.TransferRoots() == 0 || reader.NbShapes() == 0)
        throw InputError(path, 0, "IGES file holds no shape that can be transferred");
      shape = reader.OneShape();
      if (count(shape, TopAbs_SOLID) == 0) shape = sew_into_solids(shape, options.log);
    } else {
      BRep_Builder builder;
      if (!BRepTools::Read(shape, path.c_str(), builder) || shape.IsNull())
        throw InputError(path, 0, reader_failure("BREP", quiet));
    }
  } catch (const Standard_Failure& e) {
    throw InputError(path, 0, "cannot read: " + occt_message(e));
  }
  return shape;
}

TopoDS_Shape load_brep_string(const std::string& brep) {
  TopoDS_Shape shape;
  try {
    QuietOcct quiet;
    std::istringstream in(brep);
    BRep_Builder builder;
    BRepTools::Read(shape, in, builder);
    if (shape.IsNull()) throw InputError(kBrepSource, 0, "not readable BREP text" + (quiet.first().empty() ? std::string() : " (" + trim_copy(quiet.first()) + ")"));
  } catch (const Standard_Failure& e) {
    throw InputError(kBrepSource, 0, "not readable BREP text: " + occt_message(e));
  }
  return shape;
}

}  // namespace

Shape read_shape(const std::string& path, const ReadOptions& options) {
  return select_solid(load_file(path, options), path, options);
}

Shape read_brep_string(const std::string& brep, const ReadOptions& options) {
  return select_solid(load_brep_string(brep), kBrepSource, options);
}

Shape read_shape_or_brep(const std::string& source, const ReadOptions& options) {
  return is_brep_string(source) ? read_brep_string(source, options) : read_shape(source, options);
}

std::vector<Shape> read_solids(const std::string& source, const ReadOptions& options) {
  const bool brep = is_brep_string(source);
  const std::string name = brep ? std::string(kBrepSource) : source;
  const TopoDS_Shape shape = brep ? load_brep_string(source) : load_file(source, options);
  const int n = count(shape, TopAbs_SOLID);
  if (n <= 1) return {select_solid(shape, name, options)};
  // Each solid keeps the whole shape's numbers of its faces, edges and vertices (FreeCAD's for the
  // compound), so that sizes and face sets can be given and reported in them.
  TopTools_IndexedMapOfShape whole[3];
  const TopAbs_ShapeEnum kinds[3] = {TopAbs_VERTEX, TopAbs_EDGE, TopAbs_FACE};
  for (int d = 0; d < 3; ++d) TopExp::MapShapes(shape, kinds[d], whole[d]);
  std::vector<Shape> out;
  for (int k = options.solid != 0 ? options.solid : 1; k <= (options.solid != 0 ? options.solid : n); ++k) {
    ReadOptions one = options;
    one.solid = k;
    auto impl = std::make_shared<Shape::Impl>(select_solid(shape, name, one).impl());
    const TopTools_IndexedMapOfShape* own[3] = {&impl->vertices, &impl->edges, &impl->faces};
    std::vector<int>* numbers[3] = {&impl->source_vertices, &impl->source_edges, &impl->source_faces};
    for (int d = 0; d < 3; ++d)
      for (int i = 1; i <= own[d]->Extent(); ++i) numbers[d]->push_back(whole[d].FindIndex((*own[d])(i)));
    out.emplace_back(std::move(impl));
  }
  return out;
}

std::vector<std::array<int, 2>> touching_solids(const std::vector<Shape>& solids, double relative_tolerance) {
  std::vector<Bnd_Box> boxes(solids.size());
  double diagonal = 0;
  for (size_t k = 0; k < solids.size(); ++k) {
    BRepBndLib::Add(solids[k].impl().shape, boxes[k]);
    if (!boxes[k].IsVoid()) diagonal = std::max(diagonal, std::sqrt(boxes[k].SquareExtent()));
  }
  const double tolerance = relative_tolerance * diagonal;
  for (Bnd_Box& b : boxes) b.Enlarge(tolerance);
  std::vector<std::array<int, 2>> out;
  for (size_t a = 0; a < solids.size(); ++a)
    for (size_t b = a + 1; b < solids.size(); ++b) {
      if (boxes[a].IsOut(boxes[b])) continue;
      BRepExtrema_DistShapeShape d(solids[a].impl().shape, solids[b].impl().shape);
      if (d.IsDone() && d.Value() <= tolerance) out.push_back({static_cast<int>(a) + 1, static_cast<int>(b) + 1});
    }
  return out;
}

}  // namespace hexdom::cad
