# SPDX-License-Identifier: Apache-2.0
# Sourced by the callgrind scripts of bench/ (render_cost.sh, ray_cost.sh).
#
# callgrind_preload DIR BINARY: sets the array `preload` to the command prefix that lets BINARY
# start under valgrind 3.19, which stops at an instruction of libhwy's timer probe (an OpenImageIO
# dependency, run when the library loads): a stub of that one function, built in DIR, preloaded.
# Empty when BINARY does not load libhwy.
callgrind_preload() {
    local dir=$1 bin=$2
    preload=()
    if ldd "$bin" | grep libhwy > /dev/null; then  # (not grep -q: with pipefail, ldd could die of SIGPIPE)
        printf '#include <cstdint>\nnamespace hwy { namespace platform { uint64_t TimerResolution() { return 1; } } }\n' \
            > "$dir/hwy_stub.cpp"
        c++ -O2 -shared -fPIC "$dir/hwy_stub.cpp" -o "$dir/libhwy_stub.so"
        preload=(env LD_PRELOAD="$dir/libhwy_stub.so")
    fi
}
