// The usual lambda-set for std::visit: std::visit(Overloaded{[](const A&) {...}, [](const B&)
// {...}}, v). With one lambda per member and no catch-all, a new member of the variant does not
// compile until every visit handles it.
#pragma once

namespace caligo {

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

}  // namespace caligo
