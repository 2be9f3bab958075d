# Shared setup for scripts/test and scripts/demo: source it, do not run it.
#
#   frictionsim_install_deps   install the Debian packages that are missing (apt-get; sudo when not root)
#   frictionsim_configure      configure $FRICTIONSIM_BUILD_DIR (default build/, Release, Ninja if available)
#   frictionsim_build [target] build everything, or one target
#   frictionsim_python_setup [extras]
#                              create the project venv ($FRICTIONSIM_VENV, default .venv) and pip install the
#                              package with its extras (default "test"; e.g. "bench") (builds the _core
#                              extension; PyPI only, binary wheels only for the extras' packages)
#
# Environment: FRICTIONSIM_BUILD_DIR (default <repo>/build), FRICTIONSIM_CMAKE_ARGS (extra cmake arguments,
# split on spaces, e.g. "-DFRICTIONSIM_SANITIZE=ON"), FRICTIONSIM_SKIP_DEPS=1 (do not touch packages),
# FRICTIONSIM_VENV (the Python virtual environment, default <repo>/.venv).

FRICTIONSIM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
FRICTIONSIM_BUILD_DIR="${FRICTIONSIM_BUILD_DIR:-$FRICTIONSIM_ROOT/build}"
FRICTIONSIM_JOBS="$(nproc 2>/dev/null || echo 2)"
FRICTIONSIM_VENV="${FRICTIONSIM_VENV:-$FRICTIONSIM_ROOT/.venv}"

# Everything scripts/test and scripts/demo need on Debian bookworm.
FRICTIONSIM_DEB_PACKAGES=(cmake ninja-build g++ libsundials-dev libsuitesparse-dev libeigen3-dev catch2 libbenchmark-dev python3-venv python3-dev valgrind)

frictionsim_log() { printf '\n==> %s\n' "$*" >&2; }

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
    frictionsim_log "pip install .[$extras] into $FRICTIONSIM_VENV (builds frictionsim._core)"
    "$FRICTIONSIM_VENV/bin/python" -m pip install --quiet --upgrade pip
    # CMAKE_BUILD_PARALLEL_LEVEL: scikit-build-core's build uses both cores like the C++ build
    CMAKE_BUILD_PARALLEL_LEVEL="$FRICTIONSIM_JOBS" \
        "$FRICTIONSIM_VENV/bin/python" -m pip install --quiet --only-binary=scikit-sundae,sundials4py \
        "$FRICTIONSIM_ROOT[$extras]"
}
