#!/usr/bin/env bash
# The whole test suite, as CI runs it (README: ./setup.sh test). Expects the
# dependencies installed (setup.sh does that before calling this script).
#   1. format check, structure check (scripts/structure_check.py)
#   2. Release build (g++) and the CTest labels unit, cli, render; then the
#      cross label (builds build-arm64/ and runs the smoke under qemu-aarch64)
#   3. ASan+UBSan build (clang) with libFuzzer targets: unit + fuzz + cli labels
#      (the CLI tests drive every input path through the sanitized binaries; the
#      accuracy suites over whole atlases and bunnies are left to the Release run)
#   4. ThreadSanitizer build of the progressive-mesh tests (the simplifier's parallel regions)
#   5. .deb packages for amd64 and arm64, architecture checked with dpkg-deb
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
JOBS=${JOBS:-$(nproc)}
LOG_DIR=${LOG_DIR:-$ROOT/build/test-logs}
mkdir -p "$LOG_DIR"
passed=0
failed=0
failures=()
start=$(date +%s)

step() { # name command...
    local name=$1; shift
    local t0=$(date +%s)
    echo "=== $name"
    if "$@"; then
        passed=$((passed + 1)); echo "=== $name: ok ($(( $(date +%s) - t0 )) s)"
    else
        failed=$((failed + 1)); failures+=("$name"); echo "=== $name: FAILED ($(( $(date +%s) - t0 )) s)"
    fi
}

configure_and_build() { # dir [cmake args...]
    local dir=$1; shift
    cmake -S "$ROOT" -B "$dir" -G Ninja "$@" >"$LOG_DIR/$(basename "$dir")-configure.log" 2>&1 \
        || { tail -30 "$LOG_DIR/$(basename "$dir")-configure.log"; return 1; }
    cmake --build "$dir" -j "$JOBS" 2>&1 | tail -40
    return "${PIPESTATUS[0]}"
}

run_ctest() { # dir label-regex
    ctest --test-dir "$1" -L "$2" -j "$JOBS" --output-on-failure --no-tests=error
}

# The progressive-mesh unit tests under ThreadSanitizer (only what they need is built).
tsan_lod_tests() {
    cmake -S "$ROOT" -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBODY_SANITIZE_THREAD=ON \
        -DBODY_BUILD_BENCH=OFF -DBODY_WITH_IMPORT=OFF >"$LOG_DIR/build-tsan-configure.log" 2>&1 \
        || { tail -30 "$LOG_DIR/build-tsan-configure.log"; return 1; }
    cmake --build build-tsan -j "$JOBS" --target test_lod test_tiling test_shared 2>&1 | tail -20
    [ "${PIPESTATUS[0]}" -eq 0 ] || return 1
    TSAN_OPTIONS=halt_on_error=1 build-tsan/bin/test_lod --gtest_brief=1 || return 1
    # The interpolation guard's layered search and the OBJ writer on threads.
    TSAN_OPTIONS=halt_on_error=1 build-tsan/bin/test_tiling --gtest_brief=1 --gtest_filter='SelfIntersections.*' \
        || return 1
    TSAN_OPTIONS=halt_on_error=1 build-tsan/bin/test_shared --gtest_brief=1 --gtest_filter='ObjIo.*'
}

check_debs() {
    local ok=0 deb arch
    (cd build && cpack -G DEB >/dev/null) || return 1
    (cd build-arm64 && cpack -G DEB >/dev/null) || return 1
    for pair in "build:amd64" "build-arm64:arm64"; do
        deb=$(ls "${pair%%:*}"/bodygen_*.deb | head -1)
        arch=$(dpkg-deb -f "$deb" Architecture)
        dpkg-deb -I "$deb" | grep -E '^ (Package|Version|Architecture|Depends):'
        dpkg-deb -c "$deb" | grep -E 'bin/(bodygen|bodyview)$' || { echo "$deb lacks the binaries"; ok=1; }
        # The service (packaging/): unit, user, configuration as a conffile, sample exhibit.
        local files conffiles
        files=$(dpkg-deb -c "$deb" | awk '{print $6}')
        conffiles=$(dpkg-deb -I "$deb" conffiles)
        for f in ./usr/lib/systemd/system/bodyview.service ./usr/lib/sysusers.d/bodyview.conf \
                 ./etc/bodyview/bodyview.conf ./usr/share/bodyview/exhibit/scene.json; do
            grep -qx "$f" <<<"$files" || { echo "$deb lacks $f"; ok=1; }
        done
        grep -qx /etc/bodyview/bodyview.conf <<<"$conffiles" || { echo "$deb: no conffile"; ok=1; }
        [ "$arch" = "${pair##*:}" ] || { echo "$deb: architecture $arch, expected ${pair##*:}"; ok=1; }
        scripts/check-deb-depends.sh "$deb" || ok=1
    done
    return $ok
}

# Accuracy suites (minutes each under ASan, no input path of their own).
ASAN_SKIP='BunnyAccuracy|LodBunny.EveryLevel|AalAtlas'

step "format check" scripts/format.sh --check
step "structure check (file and function sizes)" python3 scripts/structure_check.py
step "release build" configure_and_build build -DCMAKE_BUILD_TYPE=Release -DBODY_BUILD_BENCH=ON
step "release tests (unit, cli, render)" run_ctest build 'unit|cli|render'
# -V: the log shows the `file` line of every arm64 binary and each comparison.
step "cross smoke (aarch64 under qemu)" ctest --test-dir build -L cross -V --no-tests=error
step "sanitizer build (clang, ASan+UBSan, libFuzzer)" configure_and_build build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DBODY_SANITIZE=ON -DBODY_FUZZ=ON -DBODY_BUILD_BENCH=OFF
step "sanitizer tests (unit, fuzz)" env ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan -L 'unit|fuzz' -j "$JOBS" --output-on-failure --no-tests=error
# Leak checks off here: the drivers' (Mesa, EGL) allocations at exit are not ours.
step "sanitizer tests (cli)" env ASAN_OPTIONS=detect_leaks=0:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan -L cli -E "$ASAN_SKIP" -j "$JOBS" --output-on-failure --no-tests=error
step "thread sanitizer (progressive meshes, guard search, OBJ writer)" tsan_lod_tests
step "debian packages (amd64, arm64)" check_debs

echo
echo "test.sh: wall time $(( $(date +%s) - start )) s"
for f in "${failures[@]}"; do echo "FAILED: $f"; done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
