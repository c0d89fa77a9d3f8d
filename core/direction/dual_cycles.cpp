#include "direction/dual_cycles.h"

#include <algorithm>

#include "common/union_find.h"

namespace tvf {
namespace {

// The counter-clockwise cycle around vertex v crosses an interior edge from the face in which the edge runs
// into v to the face in which it runs out of v.
void vertexSigns(const MeshTopology& t, const FaceConnection& c, DualCycles& d) {
  const int32_t entries = static_cast<int32_t>(c.faceF.size());
  d.entryHigh.resize(entries);
  d.entryLow.resize(entries);
  d.highSign.resize(entries);
  std::vector<int8_t> signInF(entries, 0);
  for (int32_t k = 0; k < entries; ++k) {
    const int32_t e = d.edgeOfEntry[k], f = c.faceF[k];
    for (int corner = 0; corner < 3; ++corner)
      if (t.edgeOf(f, corner) == e) signInF[k] = static_cast<int8_t>(t.signOf(f, corner));
    d.entryLow[k] = t.edgeVertices[2 * e];
    d.entryHigh[k] = t.edgeVertices[2 * e + 1];
    // signInF = +1: f runs low -> high, into the high end, so the cycle around the high end leaves f (-1).
    d.highSign[k] = static_cast<int8_t>(-signInF[k]);
  }
}

void dualTree(const MeshTopology& t, const FaceConnection& c, DualCycles& d, std::vector<uint8_t>& inTree) {
  std::vector<std::vector<int32_t>> faceEntries(t.numFaces);
  for (int32_t k = 0; k < static_cast<int32_t>(c.faceF.size()); ++k) {
    faceEntries[c.faceF[k]].push_back(k);
    faceEntries[c.faceG[k]].push_back(k);
  }
  d.parentEntry.assign(t.numFaces, -1);
  std::vector<uint8_t> seen(t.numFaces, 0);
  inTree.assign(c.faceF.size(), 0);
  for (int32_t start = 0; start < t.numFaces; ++start) {
    if (seen[start]) continue;
    seen[start] = 1;
    size_t head = d.treeOrder.size();
    d.treeOrder.push_back(start);
    while (head < d.treeOrder.size()) {
      const int32_t f = d.treeOrder[head++];
      for (const int32_t k : faceEntries[f]) {
        const int32_t g = c.faceF[k] == f ? c.faceG[k] : c.faceF[k];
        if (seen[g]) continue;
        seen[g] = 1;
        inTree[k] = 1;
        d.parentEntry[g] = k;
        d.treeOrder.push_back(g);
      }
    }
  }
}

// The faces from f up the dual tree to its root, f first.
std::vector<int32_t> pathToRoot(const DualCycles& d, const FaceConnection& c, int32_t f) {
  std::vector<int32_t> faces{f};
  while (d.parentEntry[f] >= 0) {
    const int32_t k = d.parentEntry[f];
    f = c.faceF[k] == f ? c.faceG[k] : c.faceF[k];
    faces.push_back(f);
  }
  return faces;
}

// The cycle of cotree entry k: across k from faceG to faceF, then down the tree's path back to faceG.
DualCycle fundamentalCycle(const DualCycles& d, const FaceConnection& c, int32_t k) {
  std::vector<int32_t> fromF = pathToRoot(d, c, c.faceF[k]), fromG = pathToRoot(d, c, c.faceG[k]);
  while (fromF.size() > 1 && fromG.size() > 1 && fromF[fromF.size() - 2] == fromG[fromG.size() - 2]) {
    fromF.pop_back();
    fromG.pop_back();
  }
  DualCycle cycle;
  cycle.entries.push_back(k);
  cycle.signs.push_back(1);
  auto cross = [&](int32_t entry, int32_t to) {
    cycle.entries.push_back(entry);
    cycle.signs.push_back(static_cast<int8_t>(c.faceF[entry] == to ? 1 : -1));
  };
  for (size_t i = 0; i + 1 < fromF.size(); ++i)
    cross(d.parentEntry[fromF[i]], fromF[i + 1]);  // up from faceF
  for (size_t i = fromG.size() - 1; i > 0; --i) cross(d.parentEntry[fromG[i - 1]], fromG[i - 1]);  // down
  return cycle;
}

// The sum of the partial cycles around a boundary loop's vertices: the dual cycle running along the loop.
DualCycle loopCycle(const MeshTopology& t, const DualCycles& d, const std::vector<int32_t>& loop,
                    const std::vector<std::vector<int32_t>>& vertexEntries) {
  std::vector<int32_t> coefficient(d.edgeOfEntry.size(), 0);
  std::vector<int32_t> touched;
  std::vector<int32_t> vertices;
  for (const int32_t e : loop) {
    vertices.push_back(t.edgeVertices[2 * e]);
    vertices.push_back(t.edgeVertices[2 * e + 1]);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  for (const int32_t v : vertices)
    for (const int32_t k : vertexEntries[v]) {
      coefficient[k] += d.entryHigh[k] == v ? d.highSign[k] : -d.highSign[k];
      touched.push_back(k);
    }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  DualCycle cycle;
  for (const int32_t k : touched)
    if (coefficient[k] != 0) {
      cycle.entries.push_back(k);
      cycle.signs.push_back(static_cast<int8_t>(coefficient[k]));
    }
  return cycle;
}

}  // namespace

DualCycles dualCycles(const MeshTopology& t, const FaceConnection& c) {
  DualCycles d;
  const int32_t entries = static_cast<int32_t>(c.faceF.size());
  for (int32_t e = 0; e < t.numEdges; ++e)
    if (t.edgeFaces[2 * e] >= 0 && t.edgeFaces[2 * e + 1] >= 0) d.edgeOfEntry.push_back(e);
  vertexSigns(t, c, d);

  // Vertex cycles: every interior vertex but the last of each closed component.
  d.vertexRow.assign(t.numVertices, -1);
  std::vector<int32_t> lastOfComponent(t.components.size(), -1);
  for (int32_t v = 0; v < t.numVertices; ++v)
    if (t.vertexComponent[v] >= 0 && !t.isBoundaryVertex[v]) lastOfComponent[t.vertexComponent[v]] = v;
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (t.vertexComponent[v] < 0 || t.isBoundaryVertex[v] || t.vertexFaceCount[v] == 0) continue;
    const ComponentInfo& component = t.components[t.vertexComponent[v]];
    if (component.boundaryLoops == 0 && lastOfComponent[t.vertexComponent[v]] == v) continue;
    d.vertexRow[v] = d.vertexRows++;
  }

  // Tree-cotree: a dual spanning tree, a primal spanning tree of the remaining edges (boundary edges first,
  // so that it holds all but one edge of each loop), and the entries in neither close one handle cycle each.
  std::vector<uint8_t> inDualTree;
  dualTree(t, c, d, inDualTree);
  UnionFind primal(t.numVertices);
  for (const auto& loop : t.boundaryLoops)
    for (const int32_t e : loop) primal.unite(t.edgeVertices[2 * e], t.edgeVertices[2 * e + 1]);
  for (int32_t k = 0; k < entries; ++k) {
    if (inDualTree[k]) continue;
    const int32_t e = d.edgeOfEntry[k];
    if (primal.unite(t.edgeVertices[2 * e], t.edgeVertices[2 * e + 1])) continue;
    d.generators.push_back(fundamentalCycle(d, c, k));
  }

  // All but one boundary loop of each component.
  std::vector<std::vector<int32_t>> vertexEntries(t.numVertices);
  for (int32_t k = 0; k < entries; ++k) {
    vertexEntries[d.entryHigh[k]].push_back(k);
    vertexEntries[d.entryLow[k]].push_back(k);
  }
  std::vector<uint8_t> componentHasLoop(t.components.size(), 0);
  for (const auto& loop : t.boundaryLoops) {
    if (loop.empty()) continue;
    const int32_t component = t.edgeComponent[loop.front()];
    if (!componentHasLoop[component]) {
      componentHasLoop[component] = 1;
      continue;
    }
    d.generators.push_back(loopCycle(t, d, loop, vertexEntries));
  }
  return d;
}

}  // namespace tvf
