// Compiled by the Layout.* tests with another target's include paths: a stage's private header
// (here the binding stage's) must not be found outside libknit and its own tests.
#include "binding/binding_chain.hpp"
