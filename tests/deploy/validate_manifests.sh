#!/usr/bin/env bash
# Checks what deploy/ ships without a cluster or a Docker engine:
#  1. Kubernetes manifests (deploy/k8s/*.yaml) against the Kubernetes API
#     schemas: tests/deploy/validate/validate.mjs with kubernetes-models,
#     pinned by package-lock.json and installed with `npm ci` into WORK;
#     and a broken manifest must be refused (the validator is live).
#  2. The compose file with `docker-compose config` (Debian's
#     docker-compose 1.29: the Compose schema, no engine needed); and that
#     its nginx mounts the locations file the replica test runs.
#  3. The Dockerfile's runtime stage names the Debian package of every
#     shared library meshwave-server and meshwave link directly (readelf +
#     dpkg -S on the built binaries).
#
# Usage: validate_manifests.sh WORK_DIR SERVER_BINARY CLI_BINARY
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
work=${1:?work directory}
binaries=("${@:2}")
fail() { echo "FAIL: $*" >&2; exit 1; }

# --- 1. Kubernetes ---------------------------------------------------------
command -v node > /dev/null || fail "node not found (bash deploy/install-deps.sh)"
mkdir -p "$work"
# npm ci only when the pinned set changed since the last run.
if ! cmp -s "$here/validate/package-lock.json" "$work/package-lock.json" ||
   [[ ! -d $work/node_modules/kubernetes-models ]]; then
  cp "$here/validate/package.json" "$here/validate/package-lock.json" "$work/"
  (cd "$work" && npm ci --no-audit --no-fund --loglevel=error) || fail "npm ci"
fi
cp "$here/validate/validate.mjs" "$work/"
node "$work/validate.mjs" "$root"/deploy/k8s/*.yaml || fail "Kubernetes manifests"

bad=$work/broken.yaml
cat > "$bad" << 'YAML'
apiVersion: apps/v1
kind: Deployment
metadata: {name: broken}
spec:
  replicas: two
  selector: {matchLabels: {app: x}}
  template:
    metadata: {labels: {app: x}}
    spec:
      containers:
        - name: c
          image: x
          livenessProbe: {httpGet: {path: /healthz}}
YAML
if out=$(node "$work/validate.mjs" "$bad" 2>&1); then fail "a broken manifest passed: $out"; fi
grep -q "replicas must be integer" <<< "$out" || fail "unexpected report for the broken manifest: $out"
grep -q "must have required property port" <<< "$out" ||
  fail "unexpected report for the broken manifest: $out"
echo "refused as expected: $bad"

# --- 2. compose ------------------------------------------------------------
command -v docker-compose > /dev/null || fail "docker-compose not found (bash deploy/install-deps.sh)"
(cd "$root/deploy" &&
  MESHWAVE_PG_PASSWORD=check MESHWAVE_UPLOAD_TOKEN=check \
    docker-compose -f compose.yaml --profile tools config -q) || fail "deploy/compose.yaml"
# Without the secrets it must refuse to start.
if (cd "$root/deploy" && env -u MESHWAVE_PG_PASSWORD -u MESHWAVE_UPLOAD_TOKEN \
      docker-compose -f compose.yaml config -q) 2> /dev/null; then
  fail "compose.yaml accepted missing secrets"
fi
grep -q '\./nginx/meshwave-locations.conf:/etc/nginx/meshwave-locations.conf' "$root/deploy/compose.yaml" ||
  fail "compose's nginx does not mount nginx/meshwave-locations.conf"
grep -q 'include /etc/nginx/meshwave-locations.conf;' "$root/deploy/nginx/nginx.conf" ||
  fail "deploy/nginx/nginx.conf does not include meshwave-locations.conf"
echo "deploy/compose.yaml valid"

# --- 3. Dockerfile runtime libraries ------------------------------------------
dockerfile=$root/deploy/Dockerfile
runtime=$(sed -n '/^FROM debian:12-slim$/,$p' "$dockerfile")
# Essential in debian:12-slim, never installed explicitly.
base="libc6 libstdc++6 libgcc-s1"
for bin in "${binaries[@]}"; do
  [[ -x $bin ]] || fail "no binary $bin"
  for lib in $(readelf -d "$bin" | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p'); do
    path=$(ldd "$bin" | awk -v l="$lib" '$1 == l { print $3 }')
    [[ -n $path ]] || fail "$bin: $lib not found by ldd"
    real=$(readlink -f "$path")
    pkg=$(dpkg -S "$real" 2> /dev/null | head -1 | cut -d: -f1) ||
      pkg=$(dpkg -S "$path" 2> /dev/null | head -1 | cut -d: -f1) || true
    [[ -n $pkg ]] || fail "$bin: no Debian package owns $path"
    if [[ " $base " == *" $pkg "* ]]; then continue; fi
    grep -qw -- "$pkg" <<< "$runtime" ||
      fail "$(basename "$bin") links $lib from $pkg, which the Dockerfile's runtime stage does not install"
  done
done
echo "deploy/Dockerfile runtime stage covers the libraries of: ${binaries[*]##*/}"
# The image serves /viewer/: its build stage must build the WebAssembly
# decoder (emscripten and node come with install-deps.sh's `server` set).
build_stage=$(sed -n '1,/^FROM debian:12-slim$/p' "$dockerfile")
grep -q 'install-deps.sh server' <<< "$build_stage" ||
  fail "the Dockerfile's build stage does not install the viewer's decoder toolchain (install-deps.sh server)"
grep -q 'emscripten' <(sed -n '/^viewer=(/,/^)/p' "$root/deploy/install-deps.sh") ||
  fail "install-deps.sh's viewer set does not install emscripten"
grep -q 'meshwave_decoder.js' <<< "$build_stage" ||
  fail "the Dockerfile's build stage does not check that the viewer got its decoder"
echo "deploy/Dockerfile build stage builds the viewer's decoder"
echo "deploy checks passed"
