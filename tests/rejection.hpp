// Shared by the tests that check bad input: what an InvalidParameter names, or says.
#pragma once

#include <string>

#include <frictionsim/error.hpp>

/// The parameter() of the InvalidParameter that f throws, or "<nothing thrown>".
template <class F>
std::string rejected_parameter(F&& f) {
    try {
        f();
    } catch (const frictionsim::InvalidParameter& e) {
        return e.parameter();
    }
    return "<nothing thrown>";
}

/// The what() of the InvalidParameter that f throws, or "<nothing thrown>".
template <class F>
std::string rejection_message(F&& f) {
    try {
        f();
    } catch (const frictionsim::InvalidParameter& e) {
        return e.what();
    }
    return "<nothing thrown>";
}
