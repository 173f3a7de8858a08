#!/bin/bash
# Lists shared libraries needed by .dev/bin/mpmxdem and by every ELF in .dev/root
# (orterun, orted, MCA/PMIx components, libraries) that are neither in the bundle
# nor in the excluded glibc/libstdc++/libgcc_s set, and any "not found".
cd "$(dirname "$0")/.." || exit 1
R=.dev/root; ML=usr/lib/x86_64-linux-gnu
EXCL='^(linux-vdso|ld-linux-x86-64|libc|libm|libmvec|libpthread|libdl|librt|libresolv|libutil|libanl|libthread_db|libstdc\+\+|libgcc_s)\.so'
bad=0; nf=0
while IFS= read -r f; do
  head -c4 "$f" | grep -q ELF || continue
  nf=$((nf+1))
  while read -r l; do
    case $l in
      *"not found"*) echo "MISSING ($f): $l"; bad=1; continue;;
      *"=>"*) ;;
      *) continue;;
    esac
    n=$(awk '{print $1}' <<<"$l"); n=$(basename "$n")
    [[ $n =~ $EXCL ]] && continue
    [ -e "$R/$ML/$n" ] || { echo "NOT IN BUNDLE ($f): $n"; bad=1; }
  done < <(ldd "$f" 2>&1)
done < <(echo .dev/bin/mpmxdem; find "$R" -type f \( -name '*.so*' -o -path '*/bin/*' \))
echo "check.sh: $nf ELF files checked, $([ $bad = 0 ] && echo OK || echo PROBLEMS)"
exit $bad
