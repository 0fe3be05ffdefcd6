// ModelError lives with the other errors in pdesurf/error.hpp; this header is kept so that
// code including it by its old name compiles.
#pragma once

#include "pdesurf/error.hpp"
