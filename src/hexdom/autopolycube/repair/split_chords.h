// Chords: edges inside a chart whose two ends lie on the chart's boundary. On the polycube such an
// edge can lie on a straight side of the chart's polygon and leave a flat triangle; splitting it at
// its midpoint gives the triangle an interior vertex.
#pragma once

#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

/// Splits every chord of `labels` at its midpoint (triangles with one, two or three chords become
/// two, three or four); labels carry over. `count` receives the number of chords split.
mesh::SurfaceMesh split_chords(const mesh::SurfaceMesh& labels, const ChartGraph& graph, int* count = nullptr);

}  // namespace hexdom::autopolycube
