// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// if_satisfied_t<Ok, F, A...>: F<A...> when Ok, else a placeholder, for the return type of a
/// constrained entry point that names a type from its argument's traits. Clang 14 substitutes
/// the return type before it checks the constraints, so `tubes_result<skeleton_point_t<G>>`
/// fails first on the alias and the message never names the concept; through this helper the
/// signature stays valid for any G and the failed concept is what both compilers report.

namespace cellforge::detail {

/// Stands in for the return type of a call whose concept is not satisfied (never returned).
struct unsatisfied_concept {};

template <bool Ok, template <class...> class F, class... A>
struct if_satisfied {
  using type = unsatisfied_concept;
};
template <template <class...> class F, class... A>
struct if_satisfied<true, F, A...> {
  using type = F<A...>;
};

/// F<A...> when Ok (F an unconstrained alias template), else unsatisfied_concept. O(1), compile time.
template <bool Ok, template <class...> class F, class... A>
using if_satisfied_t = typename if_satisfied<Ok, F, A...>::type;

}  // namespace cellforge::detail
