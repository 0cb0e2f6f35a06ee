// Every field of Particles, in declaration order, for code that must move a parcel whole
// (the migration buffers and their tests). The list itself is cgdem::for_each_field in
// particles/particles.hpp, shared with Particles::reorder and the checkpoint.
#pragma once
#include "particles/particles.hpp"

namespace cgdem::parallel {

using cgdem::for_each_field;

}  // namespace cgdem::parallel
