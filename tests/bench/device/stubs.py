# Makes stub shared libraries for the libraries the device check does not use: every
# symbol the binaries import from one is defined (functions return 0, data is zeroes).
import subprocess, os, re, sys
STUB = ['libopenal.so.1','libcurl.so.4','libavformat.so.59','libavcodec.so.59','libswscale.so.6',
        'libswresample.so.4','libavutil.so.57','libsndfile.so.1','libtiff.so.6','libgdcmMSFF.so.3.0',
        'libgdcmDSED.so.3.0','libgdcmCommon.so.3.0','libopenvdb.so.10.0','libtbb.so.12',
        'libImath-3_1.so.29','libOSMesa.so.8']
bins = sys.argv[1:]
def find(n):
    for d in ['/lib/x86_64-linux-gnu','/usr/lib/x86_64-linux-gnu']:
        p = os.path.join(d, n)
        if os.path.exists(p): return p
undef = set()
for b in bins:
    for line in subprocess.run(['nm','-D',b],capture_output=True,text=True).stdout.splitlines():
        undef.add(line.split()[-1].split('@')[0])
os.makedirs('stubs', exist_ok=True)
for lib in STUB:
    real = find(lib)
    defs = {}
    for line in subprocess.run(['nm','-D','-S','--defined-only',real],capture_output=True,text=True).stdout.splitlines():
        f = line.split()
        if len(f) == 4: _, size, t, name = f
        elif len(f) == 3: _, t, name = f; size = '8'
        else: continue
        name = name.split('@')[0]
        if name in undef: defs[name] = (t, int(size, 16))
    asm = ['.text']
    for n,(t,s) in defs.items():
        if t in 'TtWi':
            asm += [f'.globl {n}', f'.type {n},@function', f'{n}:', 'xor %eax,%eax', 'ret']
    asm.append('.data')
    for n,(t,s) in defs.items():
        if t not in 'TtWi':
            asm += [f'.globl {n}', f'.type {n},@object', f'.size {n},{max(s,1)}', '.balign 16', f'{n}:', f'.zero {max(s,1)}']
    open(f'stubs/{lib}.s','w').write('\n'.join(asm)+'\n')
    subprocess.run(['gcc','-shared','-nostdlib','-o',f'stubs/{lib}',f'-Wl,-soname,{lib}',f'stubs/{lib}.s'],check=True)
    print(lib, len(defs))
