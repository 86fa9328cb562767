// Placeholder until the smooth contact lands (issue: smooth contact).
#include "contact/contact.hpp"

#include <limits>

namespace fdem {

void build_contact_topology(Model&) {}
void init_contact_state(const Model&, State&) {}
void add_contact_forces(const Model&, State&) {}
Real contact_stable_dt(const Model&) { return std::numeric_limits<Real>::infinity(); }

}  // namespace fdem
