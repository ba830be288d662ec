// Points up: the test tree of the ctest entry layers.catches_an_upward_include.
#pragma once
#include "harness/cli/cli.hpp"
