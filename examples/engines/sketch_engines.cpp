// SPDX-License-Identifier: MIT
// The line-drawing engines compiled once for the project's own programs (sketch2cells and the
// sketch tests build with CELLFORGE_EXTERN_SKETCH and link this object): one compile of the
// engine instead of one per program, as docs/sketch.md ("Compile time") advises a user to do.
#include "cellforge/sketch/instantiate.hpp"
