#!/usr/bin/env bash
# The Python package's tests (python/tests, pytest), run by scripts/test.sh after the cargo tests:
# a virtualenv under the target directory with python/requirements-dev.txt (made once per
# requirements content), the package built by maturin into a wheel and installed there, then
# pytest with JBEARING_CLI = the jbearing binary of the same checkout (the tests compare the
# package's results with the CLI's HDF5 files).
#
# The wheel is built with the `dev` profile: the dependencies are the ones `cargo test` has just
# built (the test profile shares them), so only our two crates (at opt-level 1), pyo3 and the
# binding crate compile here. (`--profile test` would build the library as a test harness.) A
# user's `pip install ./python` builds the release profile instead (see README "Python").
set -euo pipefail
cd "$(dirname "$0")/.."
target=${CARGO_TARGET_DIR:-target}
venv="$target/tmp/python-package-venv"
requirements=python/requirements-dev.txt
stamp="$venv/jbearing-requirements.txt"
wanted=$(cat "$requirements" examples/python/requirements.txt)
if [ ! -x "$venv/bin/python" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$wanted" ]; then
    rm -rf "$venv"
    "${JBEARING_PYTHON:-python3}" -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check -r "$requirements"
    printf '%s' "$wanted" > "$stamp"
fi
export VIRTUAL_ENV="$(cd "$venv" && pwd)"
export PATH="$VIRTUAL_ENV/bin:$PATH"

# The CLI binary the tests compare with: the one `cargo test` built (test profile; the numbers do
# not depend on the optimisation level, Rust does not reassociate floating-point operations).
cli=$(cargo build --profile test --bin jbearing --message-format=json-render-diagnostics \
    | python -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable"):
        print(m["executable"])')
wheels="$target/tmp/python-wheels"
rm -rf "$wheels"
maturin build --quiet --profile dev --auditwheel skip --compatibility linux --manifest-path python/Cargo.toml --out "$wheels"
pip install --quiet --disable-pip-version-check --force-reinstall --no-deps "$wheels"/jbearing-*.whl
JBEARING_CLI="$cli" python -m pytest python/tests -q -p no:cacheprovider
