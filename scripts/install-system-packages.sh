#!/usr/bin/env bash
# Installs the Debian packages swarmcollide builds against, if any is missing.
# As root it installs them; otherwise it prints the command to run and fails.
set -euo pipefail

# libasan8 and libubsan1 (make test-sanitize) come with build-essential's gcc-12 already; they are
# listed so that the sanitizer runtimes are a stated requirement, not an accident.
packages=(
  build-essential libasan8 libubsan1 cmake ninja-build pkg-config git
  python3 python3-dev python3-venv
  libeigen3-dev libqhull-dev libfcl-dev libccd-dev liblbfgspp-dev
  libgtest-dev libbenchmark-dev
)

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Abbrev}' "$package" 2>/dev/null || true)
  [[ "$status" == ii* ]] || missing+=("$package")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

command="apt-get install -y --no-install-recommends ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "swarmcollide needs these Debian packages, which are missing: ${missing[*]}" >&2
  echo "Install them as root, then run make again:" >&2
  echo "  apt-get update && $command" >&2
  exit 1
fi

echo "Installing Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
$command
