#!/bin/bash
# The device check (run on the lent GPU machine with `.gpu/b` carried, see README.md): the
# real renderer through EGL, snapshots of the project's worlds against their baselines and
# of CThead's whole stream on every splat path; then bench_splats: the three paths, the GL
# paths' float layer by format (GHOSTSPACE_SPLAT_LAYER) and the level-of-detail cuts.
# Writes $OUT/snapshots.txt, $OUT/bench.txt and $OUT/pics.tgz.
cd "$(dirname "$0")/../../.." || exit 1
export LD_LIBRARY_PATH=$PWD/.gpu/b/lib GHOSTSPACE_GL=egl
V=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f $V ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$V
OUT=${OUT:-/tmp/device-check}
mkdir -p $OUT/pics
B=.gpu/b/bin D=.gpu/b/data L=tests/render/baselines A=assets/worlds
quiet() { grep -v "no version information"; }
snap() { # NAME[@TAG] WxH WORLD [OPTIONS...]: compared with the baseline NAME.png if any
  local n=$1 s=$2 w=$3
  shift 3
  timeout 120 $B/ghostspace --snapshot $OUT/pics/$n.png --size $s "$w" "$@" 2>$OUT/pics/$n.err
  printf '%-30s rc=%d ' "$n" $?
  if [ -f $L/${n%%@*}.png ]; then $B/compare_png $OUT/pics/$n.png $L/${n%%@*}.png | cut -d' ' -f1-3; else echo; fi
}
{
  nvidia-smi -L
  $B/ghostspace encode $D/CThead.nhdr -o /tmp/cthead_all.qnv --no-progress
  for w in welcome features media/background media/textures media/texture_transform text; do
    snap "$(echo $w | tr / _)" 300x300 $A/$w.wrl
  done
  for w in environment_light volume_data layout texture_projection volume_styles; do
    snap $w 300x300 $A/$w.x3dv
  done
  snap layers_t1 300x300 $A/layers.x3dv --time 1
  snap particles_t1.5 300x300 $A/particles.x3dv --time 1.5 --load-time 0
  for p in gpu geometry cpu; do
    snap gaussian_splats_node@$p 320x240 tests/data/splats/gaussian_splats_node.x3dv --splat-path $p
    snap bunny_splats@$p 200x200 $D/bun_zipper.ply --mode splats --splat-path $p
    snap cthead_all@$p 400x400 /tmp/cthead_all.qnv --splat-path $p
  done
  for p in gpu geometry; do
    echo -n "cthead_all $p against cpu: "
    $B/compare_png $OUT/pics/cthead_all@$p.png $OUT/pics/cthead_all@cpu.png | cut -d' ' -f1-3
  done
} 2>&1 | quiet | tee $OUT/snapshots.txt
tar czf $OUT/pics.tgz -C $OUT pics && rm -rf $OUT/pics
{
  timeout 100 $B/bench_splats 400x400 --millions 0 --frames 5 $D/bunny.spz $D/cthead.spz /tmp/cthead_all.qnv
  for m in off float16 float32; do
    echo "== GHOSTSPACE_SPLAT_LAYER=$m"
    GHOSTSPACE_SPLAT_LAYER=$m timeout 60 $B/bench_splats 1920x1080 --millions 0 --frames 5 --path gpu \
      $D/bunny.spz $D/cthead.spz /tmp/cthead_all.qnv
  done
  for p in gpu cpu; do
    timeout 60 $B/bench_splats 400x400 --millions 0 --frames 5 --cuts-only --path $p \
      --distances 1.5,3,6,12,24,48 $D/bunny.spz $D/cthead.spz
  done
} 2>&1 | quiet | tee $OUT/bench.txt
