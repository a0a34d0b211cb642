import time, sys, numpy as np, scipy.fft
sys.path.insert(0, '.')
from noiselab.snow import snow
from noiselab.snow.tent import tent_columns, assemble, pruned_irfftn
from noiselab.snow.render import rescale_opacity
from noiselab.spectral import spectral_noise
def med(f,n=7):
    ts=[]
    for _ in range(n):
        t=time.perf_counter(); f(); ts.append(time.perf_counter()-t)
    return np.median(ts)*1e3
snow((4,32,32),seed=0); spectral_noise((8,8),seed=0)
shape=(64,512,512); T,H,W=shape
S=np.ones((T,H,W//2+1),np.complex64)
for w in (1,2,4,16):
    fl=med(lambda: scipy.fft.irfftn(S,s=shape,workers=w))
    sn=med(lambda: snow(shape,seed=0,workers=w))
    cols=None
    def build():
        global cols, C
        cols=tent_columns(shape,c=1.0,band=(16,128),thickness=0.1,direction=(0,1),pan=(0,0),exponent=1.0)
        C=assemble(cols,np.random.default_rng(0),"uniform",np.float32)
    b=med(build)
    out=np.empty(shape,np.float32)
    ff=med(lambda: pruned_irfftn(C.copy(),cols,out,workers=w))
    rs=med(lambda: rescale_opacity(out,1.5,lo=-1.0,hi=1.0))
    print(f"snow w={w}: floor {fl:.1f} snow {sn:.1f} ({sn/fl:.2f}) build {b:.1f} fft {ff:.1f} rescale {rs:.1f}", flush=True)
for shape in [(1024,1024),(128,128,128)]:
    S=np.ones(shape[:-1]+(shape[-1]//2+1,),np.complex64)
    for w in (1,2,16):
        fl=med(lambda: scipy.fft.irfftn(S,s=shape,workers=w))
        for band in (None,(4,64),(2,16)):
            sn=med(lambda: spectral_noise(shape,band=band,seed=0,workers=w))
            print(f"noise {shape} {band} w={w}: floor {fl:.2f} noise {sn:.2f} ({sn/fl:.2f})", flush=True)
