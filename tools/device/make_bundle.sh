#!/bin/bash
# Builds .dev/bin/mpmxdem and .dev/root/ (runtime closure of build/mpmxdem and Debian's Open MPI
# 4.1.4) on the Debian 12 build machine, and copies install.sh, check.sh and env.sh beside them: a
# bundle to run the program on a machine without these packages (tools/device/README.md).
# Re-runnable; about 41 MB.
set -euo pipefail
REPO=$(cd "$(dirname "$0")/../.." && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
D=$REPO/.dev; R=$D/root
ML=/usr/lib/x86_64-linux-gnu
EXCL='^(linux-vdso|ld-linux-x86-64|libc|libm|libmvec|libpthread|libdl|librt|libresolv|libutil|libanl|libthread_db|libstdc\+\+|libgcc_s)\.so'

rm -rf "$R" "$D/bin"; mkdir -p "$R" "$D/bin"
strip -o "$D/bin/mpmxdem" "$REPO/build/mpmxdem"
cp "$HERE/install.sh" "$HERE/check.sh" "$HERE/env.sh" "$D/"

# put SRC [DST]: copy a file, dereferenced, to $R/DST (default: same path; /lib/* -> /usr/lib/*)
put() { local s=$1 d=${2:-$1}; d=${d/#\/lib\//\/usr\/lib\/}
        mkdir -p "$R$(dirname "$d")"; cp -L --preserve=mode "$s" "$R$d"; }

# Open MPI executables (real copies, no symlinks in the bundle)
for b in orterun orted ompi_info; do put /usr/bin/$b; done
put /usr/bin/orterun /usr/bin/mpiexec
put /usr/bin/orterun /usr/bin/mpirun
# MCA components, help files, config (regular files only: skip dev/wrapper symlinks)
for dir in $ML/openmpi/lib/openmpi3 /usr/share/openmpi /etc/openmpi \
           $ML/pmix2/lib/pmix $ML/pmix2/share; do
  find "$dir" -type f | while read -r f; do put "$f"; done
done
put $ML/openmpi/lib/ompi_monitoring_prof.so
# PMIx library at its soname (the real file lives in pmix2/lib)
put $ML/libpmix.so.2

# recursive ldd closure over every ELF in the bundle
missing=$D/missing.txt; : > "$missing"
while :; do
  new=0
  while read -r f; do
    ldd "$f" 2>/dev/null | while read -r l; do
      case $l in *"not found"*) echo "$f: $l" >> "$missing"; continue;; esac
      p=$(awk '$2=="=>" && $3 ~ /^\// {print $3}' <<<"$l"); [ -n "$p" ] || continue
      n=$(basename "$p"); [[ $n =~ $EXCL ]] && continue
      [ -e "$R$ML/$n" ] || { put "$p" "$ML/$n"; echo "+ $n"; }
    done
  done < <(find "$D/bin" "$R" -type f \( -name '*.so*' -o -perm -u+x \)) > "$D/.new"
  [ -s "$D/.new" ] || break
  cat "$D/.new"
done
rm -f "$D/.new"
sort -u -o "$missing" "$missing"
echo "missing:"; cat "$missing"
du -sh "$D"
