// conformesh — status codes and the error type: public, in include/conformesh/status.h.
#pragma once

#include "conformesh/status.h"
