// conformesh — the remesh pipeline's options, report and entry point: public, in include/conformesh/remesh.h.
#pragma once

#include "conformesh/remesh.h"
