# Shared setup for scripts/test and scripts/demo: source it, do not run it.
#
#   frictionsim_install_deps   install the Debian packages that are missing (apt-get; sudo when not root)
#   frictionsim_configure      configure $FRICTIONSIM_BUILD_DIR (default build/, Release, Ninja if available)
#   frictionsim_build [target] build everything, or one target
#   frictionsim_python_setup [extras]
#                              create the project venv ($FRICTIONSIM_VENV, default .venv), build the wheel once
#                              (frictionsim_build_wheel) and pip install that wheel with its extras (default
#                              "test"; e.g. "bench"; PyPI only, binary wheels only for the extras' packages)
#   frictionsim_build_wheel    pip wheel . into $FRICTIONSIM_WHEEL_DIR (builds the _core extension, SUNDIALS linked
#                              statically); sets FRICTIONSIM_WHEEL to the wheel's path
#   frictionsim_wheel_smoke_test DIR
#                              the wheel $FRICTIONSIM_WHEEL in a fresh venv DIR (no extras; numpy etc. from pip's
#                              cache): its extension needs no SUNDIALS shared library (readelf -d), it imports
#                              and runs (scripts/lib/wheel_smoke.py)
#   frictionsim_version        the version, from its one source (CMakeLists.txt's project(... VERSION))
#
# Environment: FRICTIONSIM_BUILD_DIR (default <repo>/build), FRICTIONSIM_CMAKE_ARGS (extra cmake arguments,
# split on spaces, e.g. "-DFRICTIONSIM_SANITIZE=ON"), FRICTIONSIM_SKIP_DEPS=1 (do not touch packages),
# FRICTIONSIM_VENV (the Python virtual environment, default <repo>/.venv), FRICTIONSIM_WHEEL_DIR (where the wheel
# goes, default <repo>/out/wheel).

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
# so scripts/check run by scripts/test counts from the same start) and how long the step before it took (also across
# that boundary: FRICTIONSIM_STEP_T0 is exported too), so a CI log shows where the time goes. frictionsim_log_total
# prints the total at the end.
export FRICTIONSIM_T0="${FRICTIONSIM_T0:-$(date +%s)}"
export FRICTIONSIM_STEP_T0="${FRICTIONSIM_STEP_T0:-$FRICTIONSIM_T0}"
frictionsim_log() {
    local now
    now="$(date +%s)"
    printf '\n==> [%5d s, the step before %4d s] %s\n' "$((now - FRICTIONSIM_T0))" "$((now - FRICTIONSIM_STEP_T0))" \
        "$*" >&2
    FRICTIONSIM_STEP_T0="$now"
}
frictionsim_log_total() {
    frictionsim_log "$* (total wall time $(( $(date +%s) - FRICTIONSIM_T0 )) s)"
}

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

frictionsim_python_setup() {
    local extras="${1:-test}"
    local python="${FRICTIONSIM_PYTHON:-python3}"
    if [[ ! -x "$FRICTIONSIM_VENV/bin/python" ]]; then
        frictionsim_log "creating venv $FRICTIONSIM_VENV"
        "$python" -m venv "$FRICTIONSIM_VENV"
    fi
    "$FRICTIONSIM_VENV/bin/python" -m pip install --quiet --upgrade pip
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
    frictionsim_log "pip wheel . into $FRICTIONSIM_WHEEL_DIR (builds frictionsim._core)"
    mkdir -p "$FRICTIONSIM_WHEEL_DIR"
    rm -f "$FRICTIONSIM_WHEEL_DIR"/frictionsim-*.whl
    # CMAKE_BUILD_PARALLEL_LEVEL: scikit-build-core's build uses both cores like the C++ build
    CMAKE_BUILD_PARALLEL_LEVEL="$FRICTIONSIM_JOBS" \
        "$FRICTIONSIM_VENV/bin/python" -m pip wheel --quiet --no-deps --wheel-dir "$FRICTIONSIM_WHEEL_DIR" \
        "$FRICTIONSIM_ROOT"
    local wheels=("$FRICTIONSIM_WHEEL_DIR"/frictionsim-*.whl)
    if ((${#wheels[@]} != 1)) || [[ ! -f "${wheels[0]}" ]]; then
        echo "error: pip wheel left ${#wheels[@]} frictionsim wheels in $FRICTIONSIM_WHEEL_DIR" >&2
        return 1
    fi
    FRICTIONSIM_WHEEL="${wheels[0]}"
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
    "$venv/bin/python" -m pip install --quiet "$FRICTIONSIM_WHEEL"
    # From the venv's directory: the wheel's files are imported, never the source tree.
    (cd "$venv" && "$venv/bin/python" "$FRICTIONSIM_ROOT/scripts/lib/wheel_smoke.py" "$(frictionsim_version)")
}
