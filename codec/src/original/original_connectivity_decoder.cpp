#include "original/original_connectivity.h"

namespace meshwave::original {}  // namespace meshwave::original
