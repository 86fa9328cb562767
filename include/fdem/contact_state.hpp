// Mutable contact data: broad-phase candidates, per-pair history and scratch buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "fdem/math.hpp"

namespace fdem {

struct ContactState {
    int32_t active_contacts = 0;  ///< pairs in contact after the last step
};

}  // namespace fdem
