#pragma once
// Connected parts of a mesh's elements: vertices joined through shared elements. A part with
// no fixed vertex leaves the map undetermined up to a translation (field deviation does not
// change under one): the L2 solve reports it, phase 1 and the active-set bound of the
// L-infinity solver hold one vertex of it, shape interpolation pins one per part.
#include <vector>

#include "strictmin/problem/problem.h"

namespace strictmin {

struct ElementParts {
  std::vector<int> part;  // #V: each vertex's part, numbered by first vertex; -1: in no element
  int count = 0;
};

// The parts of the elements flagged in `elements` (#E; null: every element).
ElementParts element_parts(const Problem& p, const std::vector<char>* elements = nullptr);

// The first vertex (in vertex order) of each part without an anchor (anchor: #V flags).
std::vector<int> unanchored_parts(const ElementParts& parts, const std::vector<char>& anchor);

// unanchored_parts of every element, anchored by the problem's fixed vertices: empty when
// every part has a fixed vertex (the L2 solve's check).
std::vector<int> unanchored_components(const Problem& p);

}  // namespace strictmin
