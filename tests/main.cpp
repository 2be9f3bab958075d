// One test binary for the whole C++ suite (build time on 2 cores); Catch2 v3 brings its own main.
#if !__has_include(<catch2/catch_all.hpp>)
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
#endif
