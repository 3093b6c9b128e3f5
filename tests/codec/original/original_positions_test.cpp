#include "original/original_positions.h"

#include <gtest/gtest.h>
