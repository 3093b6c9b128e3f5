// MW_RETURN_IF_ERROR for coroutines, which must co_return.
#ifndef MESHWAVE_CLIENT_CO_STATUS_H_
#define MESHWAVE_CLIENT_CO_STATUS_H_

#include "meshwave/status.h"

#define MWC_CO_RETURN_IF_ERROR(expr)              \
  do {                                            \
    ::meshwave::Status mwc_status_ = (expr);      \
    if (!mwc_status_.ok()) co_return mwc_status_; \
  } while (0)

#endif  // MESHWAVE_CLIENT_CO_STATUS_H_
