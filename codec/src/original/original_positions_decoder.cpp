#include "original/original_positions.h"

namespace meshwave::original {}  // namespace meshwave::original
