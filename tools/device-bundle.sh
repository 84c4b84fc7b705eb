#!/usr/bin/env bash
# Gathers what a Release build of sdgbehave needs on the lent GPU machine
# (an Ubuntu host with the NVIDIA driver and nothing else), for the device
# tool's `carry`: .gl/ holds the GL/EGL loader packages (unpacked into / there,
# as /work/shared/gpu/README.md says), .devlibs/ the Debian packages of every
# other shared library the binary links, which are unpacked into a private
# folder there and found through LD_LIBRARY_PATH; .devbin/ the binary itself.
# Usage: tools/device-bundle.sh [BUILD_DIR]   (default build/release)
# Then on the device: source tools/device-env.sh
set -euo pipefail
build="${1:-build/release}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
# In a git worktree .git is a file: ask git where the exclude file is.
exclude="$(git rev-parse --git-path info/exclude)"
mkdir -p "$(dirname "$exclude")"
for d in .gl .devlibs .devbin; do
  grep -qx "/$d/" "$exclude" 2>/dev/null || echo "/$d/" >> "$exclude"
done
mkdir -p .gl .devlibs .devbin /tmp/amd64/partial
apt_opts=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
apt-get "${apt_opts[@]}" update -qq
(cd .gl && apt-get "${apt_opts[@]}" download -qq libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 2>/dev/null)

# Packages the host already has in a newer version: glibc, the GCC runtime, zlib.
base='^(libc6|libstdc\+\+6|libgcc-s1|zlib1g|libbz2-1.0|libexpat1|liblzma5|libzstd1)$'
mapfile -t pkgs < <(ldd "$build/app/sdgbehave" | awk '/=>/ {print $3}' |
  xargs -r readlink -f | xargs -r dpkg -S 2>/dev/null | cut -d: -f1 | sort -u | grep -Ev "$base")
(cd .devlibs && rm -f ./*.deb && apt-get "${apt_opts[@]}" download -qq "${pkgs[@]}" 2>/dev/null)
cp "$build/app/sdgbehave" .devbin/
echo "device-bundle: ${#pkgs[@]} packages in .devlibs, $(du -sh .gl .devlibs .devbin | awk '{s=s" "$2"="$1} END{print s}')"
