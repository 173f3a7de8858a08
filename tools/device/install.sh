#!/bin/bash
# Run on the target, as root, from the repo root:  bash .dev/install.sh
# Copies .dev/root/* into / without overwriting anything that already exists
# (the target's own, newer libraries win), then runs ldconfig and checks.
set -u
cd "$(dirname "$0")/.." || exit 1
R=.dev/root
[ -d "$R" ] || { echo "no $R" >&2; exit 1; }
n=0; k=0
while IFS= read -r -d '' f; do
  t=/${f#./}
  if [ -e "$t" ] || [ -L "$t" ]; then k=$((k+1)); continue; fi
  mkdir -p "$(dirname "$t")" && cp --preserve=mode "$R/$f" "$t" && n=$((n+1))
done < <(cd "$R" && find . -type f -print0)
echo "installed $n files, kept $k existing"
chmod 755 /usr/bin/orterun /usr/bin/orted /usr/bin/ompi_info 2>/dev/null
cmp -s "$R/usr/bin/orterun" /usr/bin/mpiexec || echo "WARNING: /usr/bin/mpiexec is not Open MPI's orterun; use /usr/bin/orterun" >&2
chmod 755 .dev/bin/mpmxdem
ldconfig
echo "--- ldd .dev/bin/mpmxdem | grep 'not found' (should be empty):"
ldd .dev/bin/mpmxdem | grep 'not found'
bash .dev/check.sh
