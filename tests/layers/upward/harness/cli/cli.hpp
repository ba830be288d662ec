// The command line of the test tree (tests/layers/upward).
#pragma once
#include "harness/core/vocabulary.hpp"
