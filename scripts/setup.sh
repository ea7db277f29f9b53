#!/usr/bin/env bash
# Create .venv and install robotsoccer with its test tools and Ray (--backend ray). Idempotent.
# torch goes in first, pinned to the CPU wheel: a bare `torch` requirement on a machine without
# it would download the newest CUDA build (several GB); see shared notes/tooling.md §0 and §6.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
[ -x .venv/bin/python ] || "$PY" -m venv .venv
. .venv/bin/activate
export PIP_DISABLE_PIP_VERSION_CHECK=1
if ! pip show -q torch >/dev/null 2>&1; then
  pip install -q torch==2.13.0 2>&1 | grep -v "is ignored" || true
fi
pip show -q torch >/dev/null 2>&1 || { echo "setup.sh: torch failed to install" >&2; exit 1; }
pip install -q -e ".[dev,ray]" 2>&1 | grep -v "is ignored" || true
python -c "import robotsoccer, field_models, learning" || { echo "setup.sh: install failed" >&2; exit 1; }
echo "setup.sh: ready (.venv)"
