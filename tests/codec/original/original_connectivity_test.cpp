#include "original/original_connectivity.h"

#include <gtest/gtest.h>
