#!/bin/bash
# Packs what the device check (check.sh) runs into .gpu/b of the checkout: build-ci's
# ghostspace, bench_splats and compare_png, stripped; the shared libraries they need but
# glibc's (the device machine is another distribution); stubs in place of the libraries
# the check never calls (OSMesa and its 115 MB of LLVM, FFmpeg, OpenVDB, GDCM, ...:
# stubs.py), which keeps the whole under the device tool's 64 MiB; and the corpus files it
# reads. Run here after a build; then run check.sh there with `.gpu/b` carried.
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
corpus=${GS_CORPUS:-$root/../shared/corpus}
out=$root/.gpu/b
rm -rf "$out"
mkdir -p "$out"/bin "$out"/lib "$out"/data "$root"/.gpu/stubs
for x in ghostspace bench_splats compare_png; do strip -o "$out/bin/$x" "$root/build-ci/bin/$x"; done
cd "$root/.gpu"
python3 "$root/tests/bench/device/stubs.py" b/bin/ghostspace b/bin/bench_splats b/bin/compare_png
# The closure of the binaries' libraries, stopping at the stubs.
python3 - <<'PY'
import os, re, shutil, subprocess
seen, todo = set(), ['b/bin/ghostspace', 'b/bin/bench_splats', 'b/bin/compare_png']
glibc = re.compile(r'^(libc|libm|libpthread|libdl|librt|ld-linux.*)\.so')
while todo:
    out = subprocess.run(['readelf', '-d', todo.pop()], capture_output=True, text=True).stdout
    for name in re.findall(r'Shared library: \[(.*?)\]', out):
        if name in seen or glibc.match(name):
            continue
        seen.add(name)
        if os.path.exists('stubs/' + name):
            shutil.copy('stubs/' + name, 'b/lib/' + name)
            continue
        for d in ('/lib/x86_64-linux-gnu', '/usr/lib/x86_64-linux-gnu'):
            if os.path.exists(os.path.join(d, name)):
                shutil.copy(os.path.join(d, name), 'b/lib/' + name)
                todo.append(os.path.join(d, name))
                break
PY
# glvnd's EGL, opened at run time (GHOSTSPACE_GL=egl); the machine brings NVIDIA's vendor library.
for l in libEGL.so.1 libGLdispatch.so.0 libOpenGL.so.0; do cp -L /lib/x86_64-linux-gnu/$l b/lib/; done
cp "$corpus"/splat/bunny.spz "$corpus"/splat/cthead.spz "$corpus"/mesh/bunny/bun_zipper.ply \
  "$corpus"/volume/cthead/CThead.nhdr "$corpus"/volume/cthead/CThead.raw.gz b/data/
du -sh b
