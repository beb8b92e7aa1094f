#!/usr/bin/env bash
# The C++ plugin on another Debian's ParaView, from a clean clone, in a debootstrap chroot:
#
#   sudo scripts/other-paraview.sh trixie    # Debian 13: ParaView 5.13, Qt 6, glibc 2.41
#   sudo scripts/other-paraview.sh sid       # unstable:  ParaView 6.1 on VTK 9.6, Qt 6, glibc 2.43
#
# 1. makes the chroot (debootstrap --variant=minbase, from the Debian mirror this machine's apt
#    uses) unless it is there already: SCHLIEREN_CHROOT, default <repository>/../chroot-<release>;
# 2. binds /proc, /sys, /dev, /dev/pts and, when it exists, ../shared/data (read-only: the CFD
#    data some tests read) into it, and unmounts them again on exit;
# 3. clones this repository's HEAD (committed work only; SCHLIEREN_CLONE_FROM overrides) into
#    <chroot>/work/schlieren, and there installs the release's packages with scripts/common.sh
#    (which also makes the links past Debian's paraview-dev suffix bug), configures and builds;
# 4. runs a named part of the suite (SCHLIEREN_OTHER_TESTS, a ctest -R expression; the default
#    below: the engine tests, the filters' values, the pvpython pipelines with their baselines,
#    the plugin's install, MPI on 2 ranks and two GUI tests under Xvfb: python.gui, a script run
#    inside the GUI, and python.gui_apply_stop, X key and mouse events), then traces the
#    first-light image and the blunt fin (scripts/other_paraview_images.py) into
#    <chroot>/work/out/images;
# 5. when this machine has a build of its own (build/, e.g. Debian 12's), traces the same there and
#    compares the two bit for bit (else says by how many ulp they differ).
# The log, with the versions met, goes to <chroot>/work/out/other-paraview-<release>.log.
# Needs root, debootstrap and about 6-7 GB per chroot. docs/BUILDING.md has results.
set -euo pipefail

release="${1:-}"
case "$release" in
  trixie|sid) ;;
  *) echo "usage: $0 trixie|sid" >&2; exit 2 ;;
esac
if [ "$(id -u)" -ne 0 ]; then
  echo "$0 makes and enters a chroot: run it as root" >&2
  exit 1
fi
command -v debootstrap > /dev/null || { echo "debootstrap is needed: apt-get install debootstrap" >&2; exit 1; }

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="${SCHLIEREN_CHROOT:-$(dirname "$here")/chroot-$release}"
clone_from="${SCHLIEREN_CLONE_FROM:-$here}"
tests="${SCHLIEREN_OTHER_TESTS:-^(engine\..*|filters\..*|python\.(pipeline|errors|baseline|example_first_light|example_bluntfin|amr|install|mpi|mpi_compare|gui|gui_apply_stop))$}"

# the mirror apt uses here (deb822 "URIs:" or one-line "deb URL"), not the security one
mirror="$(cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources 2>/dev/null |
  sed -n -e 's/^URIs: *\([^ ]*\).*/\1/p' -e 's/^deb  *\(\[[^]]*\] *\)\{0,1\}\([^ ]*\).*/\2/p' |
  grep '/debian/\{0,1\}$' | grep -v security | head -n 1 || true)"
mirror="${mirror:-http://deb.debian.org/debian}"

if [ ! -x "$root/usr/bin/apt-get" ]; then
  echo "== debootstrap $release into $root from $mirror"
  debootstrap --variant=minbase "$release" "$root" "$mirror"
fi

mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount "${mounted[$i]}" 2> /dev/null || umount -l "${mounted[$i]}" || true
  done
}
trap cleanup EXIT
for m in proc sys dev dev/pts; do
  if ! mountpoint -q "$root/$m"; then
    mount --bind "/$m" "$root/$m"
    mounted+=("$root/$m")
  fi
done
mkdir -p "$root/work/shared/data" "$root/work/out"
if [ -d "$(dirname "$here")/shared/data" ] && ! mountpoint -q "$root/work/shared/data"; then
  mount --bind "$(dirname "$here")/shared/data" "$root/work/shared/data"
  mount -o remount,bind,ro "$root/work/shared/data"
  mounted+=("$root/work/shared/data")
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
# sid's Release file can be past its Valid-Until on a snapshot mirror
if [ "$release" = sid ]; then
  echo 'Acquire::Check-Valid-Until "false";' > "$root/etc/apt/apt.conf.d/99schlieren-snapshot"
fi
if ! chroot "$root" sh -c 'command -v git' > /dev/null; then
  chroot "$root" apt-get update -qq
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq git ca-certificates > /dev/null
fi

echo "== cloning $clone_from ($(git -C "$clone_from" rev-parse --short HEAD 2> /dev/null || echo '?')) into $root/work/schlieren"
rm -rf "$root/work/schlieren"
git clone --quiet "$clone_from" "$root/work/schlieren"

log="/work/out/other-paraview-$release.log"
status=0
chroot "$root" env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
  LANG=C.UTF-8 SCHLIEREN_TESTS="$tests" SCHLIEREN_LOG="$log" bash -c '
set -euo pipefail
cd /work/schlieren
source scripts/common.sh
exec > >(tee "$SCHLIEREN_LOG") 2>&1
echo "== $(date -u "+%Y-%m-%d %H:%M UTC"), Debian $SCHLIEREN_DEBIAN_RELEASE ($(cat /etc/debian_version)), commit $(git rev-parse --short HEAD)"
schlieren_install "${SCHLIEREN_BUILD_PACKAGES[@]}" xvfb xauth openbox xdotool x11-utils imagemagick \
  python3-numpy pkg-config
version() { dpkg-query -W -f="\${Version}" "$1" 2> /dev/null || echo "?"; }
echo "== versions: ParaView $(version paraview), VTK $(version libvtk9-dev), Qt $(dpkg-query -W -f="\${Package} \${Version}\n" "libqt[56]core[56]*" 2> /dev/null | awk "\$2 != \"\" && \$1 !~ /compat/ { v = \$2 } END { print v }")," \
  "glibc $(version libc6), GCC $(version gcc), CMake $(version cmake), Python $(version python3)," \
  "PoCL $(version pocl-opencl-icd), Open MPI $(version openmpi-bin)"
start=$(date +%s)
schlieren_build
echo "== built in $(( $(date +%s) - start )) s: $(schlieren_plugin)"
export SCHLIEREN_REQUIRE_OPENCL=1 POCL_CACHE_DIR="$SCHLIEREN_BUILD/pocl-cache"
cd "$SCHLIEREN_BUILD"
status=0
ctest --output-on-failure -j 1 -R "$SCHLIEREN_TESTS" || status=$?
# the images to hold against Debian 12 (the last step below)
pvpython ../scripts/other_paraview_images.py --plugin "$(schlieren_plugin)" --output /work/out/images || status=1
echo "== ctest and images: exit status $status"
exit $status
' || status=$?

host_plugin="$(ls "$here"/build/lib/paraview-*/plugins/Schlieren/Schlieren.so 2> /dev/null | head -n 1 || true)"
if [ -n "$host_plugin" ] && command -v pvpython > /dev/null; then
  echo "== the same images from this machine's build ($(. /etc/os-release && echo "$PRETTY_NAME"), $host_plugin)"
  rm -rf "$root/work/out/host-images"
  POCL_CACHE_DIR="$here/build/pocl-cache" pvpython "$here/scripts/other_paraview_images.py" --plugin "$host_plugin" \
    --output "$root/work/out/host-images" > /dev/null
  echo "== $release against this machine:" | tee -a "$root$log"
  /usr/bin/python3 "$here/scripts/other_paraview_images.py" --compare "$root/work/out/host-images" \
    "$root/work/out/images" 2>&1 | tee -a "$root$log" || true
fi
echo "== log: $root$log"
exit $status
