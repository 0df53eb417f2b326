// SPDX-License-Identifier: MIT
// A renamed name's old spelling is deprecated (docs/vocabulary.md): with -Werror a program
// that still writes it does not build, and the message names the new spelling.
// expect: deprecated: use tubes_options; removed in 0.8
#include "cellforge/tubes/tube_mesh.hpp"

#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
cellforge::tubes_options options;
#else
cellforge::tube_options options;
#endif
