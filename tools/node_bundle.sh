#!/bin/bash
# Packs a build for a bare x86-64 Linux machine that has no MPI, HDF5 or METIS installed (a lent
# many-core node): the stripped binaries (mpmxdem, bench_dem, bench_farm), every shared library
# they, Open MPI's launchers and its plugins need (glibc and the C++ runtime excepted: the node's
# own), Open MPI's runtime (plugins, help files) and PMIx's plugins, and env.sh, which points
# Open MPI at its new place (OPAL_PREFIX). Made for tools/bench_node.sh (docs/validation/scaling.md section 6).
#
#   tools/node_bundle.sh [BUILD] [OUT]     # default build/ and node_bundle.tar.xz (about 13 MB)
# On the node, from the repository root:
#   mkdir -p /tmp/d && tar -C /tmp/d -xJf node_bundle.tar.xz && . /tmp/d/env.sh
#   tools/bench_node.sh /tmp/d/bin OUT
# Debian 12's Open MPI 4.1.4 relocates with OPAL_PREFIX; its PMIx looks for its plugins where it
# was built (/usr/lib/x86_64-linux-gnu/pmix2): env.sh links that folder to the bundle's when the
# node has none and may write there (root), else says so.
set -euo pipefail
BUILD=$(cd "${1:-build}" && pwd)
OUT=$(realpath -m "${2:-node_bundle.tar.xz}")
MULTI=usr/lib/x86_64-linux-gnu
R=$(mktemp -d)
trap 'rm -rf "$R"' EXIT
mkdir -p "$R/bin" "$R/lib" "$R/usr/bin" "$R/usr/share" "$R/$MULTI/pmix2"
for f in "$BUILD/mpmxdem" "$BUILD/src/dem/bench_dem" "$BUILD/src/farm/bench_farm"; do
  strip -o "$R/bin/$(basename "$f")" "$f"
done
cp -a "/$MULTI/openmpi" "$R/$MULTI/"
rm -rf "$R/$MULTI/openmpi/include"
cp -a "/$MULTI/pmix2/lib" "/$MULTI/pmix2/share" "$R/$MULTI/pmix2/"
rm -f "$R/$MULTI/pmix2/lib/libpmix.a"
cp -a /usr/share/openmpi "$R/usr/share/"
for f in orterun orted ompi_info; do cp -L "/usr/bin/$f" "$R/usr/bin/"; done
ln -s orterun "$R/usr/bin/mpirun"
for o in "$R"/bin/* "$R"/usr/bin/orterun "$R"/usr/bin/orted "$R"/usr/bin/ompi_info \
         $(find "$R/usr/lib" -name "*.so*" -type f); do
  ldd "$o" 2>/dev/null | awk '/=> \//{print $3}'
done | sort -u |
  grep -v -E '/(libc|libm|libdl|libpthread|librt|ld-linux-x86-64|libstdc\+\+|libgcc_s|libresolv|libutil)\.so' |
  while read -r l; do cp -L "$l" "$R/lib/"; done
cat >"$R/env.sh" <<'ENV'
# Source after unpacking the bundle: . /path/to/bundle/env.sh
D=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export OPAL_PREFIX=$D/usr
export PMIX_MCA_mca_base_component_path=$D/usr/lib/x86_64-linux-gnu/pmix2/lib/pmix
export PMIX_MCA_pcompress_base_silence_warning=1
export LD_LIBRARY_PATH=$D/lib:$D/usr/lib/x86_64-linux-gnu/openmpi/lib
export PATH=$D/bin:$D/usr/bin:$PATH
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_pml=ob1 OMPI_MCA_btl=self,vader OMPI_MCA_mtl=^ofi OMPI_MCA_osc=^ucx,pt2pt
export OMPI_MCA_btl_base_warn_component_unused=0
if [ ! -e /usr/lib/x86_64-linux-gnu/pmix2 ]; then
  ln -s "$D/usr/lib/x86_64-linux-gnu/pmix2" /usr/lib/x86_64-linux-gnu/pmix2 2>/dev/null ||
    echo "env.sh: could not link /usr/lib/x86_64-linux-gnu/pmix2 (not root?): mpirun may fail" >&2
elif [ "$(readlink -f /usr/lib/x86_64-linux-gnu/pmix2)" != "$D/usr/lib/x86_64-linux-gnu/pmix2" ]; then
  # A node image with a PMIx of its own (the lent H200 node, 2026-11-26): mpirun loads its plugins
  # and fails ("pmix_mca_pcompress_zlib.so: undefined symbol: pmix_output_info").
  echo "env.sh: this node has its own /usr/lib/x86_64-linux-gnu/pmix2: mpirun may fail; on a" \
       "throwaway node, as root: mv it aside and source env.sh again" >&2
fi
ENV
tar -C "$R" -cJf "$OUT" .
echo "tools/node_bundle.sh: $OUT ($(du -h "$OUT" | cut -f1)); on the node: tar -C /tmp/d -xJf, . /tmp/d/env.sh"
