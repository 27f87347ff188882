#!/usr/bin/env python3
# A timeline of a ThreadPool trace (bench/pool-trace.patch, core-frame-issue11.md section 61):
#   git apply bench/pool-trace.patch; build facet_phase_times;
#   FACET_POOL_TRACE=/tmp/t.txt build/bin/facet_phase_times 2000000 0 60 2 18 1 0 f64 vtk
#   python3 bench/pool_trace.py /tmp/t.txt [build/bin/facet_phase_times]
# Per job (medians over the warm frames, us): tasks, wall, each thread's time in tasks, its idle
# (wall less that), thread 1's wake-up (job start to its first task), each thread's tail (its
# last task's end to the job's end), and the caller's serial gap before the job.
import sys, statistics as st
rows=[l.split() for l in open(sys.argv[1])]
import subprocess
key={'setUpBackFaces':'backSetup','transformKeptBackBlocks':'keptBackXf','shadePolygons':'shade','transformLatePoints':'latePts','setUpPolygons':'frontSetup','transformPoints':'transform','cullBlocksOutsideView':'cullView','paintFrontTiles':'frontRaster','paintBackTiles':'backRaster','paintTiles':'raster','resolveTiles':'resolve','MeshCache::measure':'measure','MeshCache::validate':'validate'}
binp=sys.argv[2] if len(sys.argv)>2 else '/work/wt/every39/build/bin/facet_phase_times'
names={}
for a in sorted(set(r[5] for r in rows)):
    out=subprocess.run(['addr2line','-f','-C','-e',binp,a],capture_output=True,text=True).stdout.split('\n')[0]
    for k,v in key.items():
        if 'detail::'+k+'(' in out: names[a]=v
# split frames: frame starts at cullView
frames=[];cur=[]
for r in rows:
    n=names.get(r[5],r[5])
    if n in('cullView','validate') and cur and not any(names.get(x[5])=='validate' for x in cur[-1:]):
        frames.append(cur);cur=[]
    cur.append(r)
frames.append(cur)
frames=[f for f in frames if names.get(f[0][5])=='cullView']
print(len(frames),'frames')
stats={}
for f in frames[1:]:
    prev_end=None
    for r in f:
        n=names.get(r[5],r[5]); t0,t1=float(r[1]),float(r[2])
        b0,b1=float(r[6]),float(r[7]); fs0,fs1=float(r[8]),float(r[9]); le0,le1=float(r[10]),float(r[11])
        wall=t1-t0
        gap= t0-prev_end if prev_end else 0
        prev_end=t1
        d=stats.setdefault(n,[])
        d.append(dict(wall=wall,b0=b0,b1=b1,cnt=int(r[3])+int(r[4]),k0=int(r[12]),k1=int(r[13]),gap=gap,
            wake=(fs1-t0) if int(r[13]) else float('nan'), tail0=t1-le0 if int(r[12]) else wall, tail1=t1-le1 if int(r[13]) else wall))
    stats.setdefault('_frame',[]).append(dict(wall=float(f[-1][2])-float(f[0][1])))
order=['cullView','transform','frontSetup','raster','frontRaster','latePts','keptBackXf','backSetup','backRaster','shade','resolve']
print(f"{'job':12s} {'tasks':>5s} {'wall':>7s} {'busy0':>7s} {'busy1':>7s} {'idle0':>6s} {'idle1':>6s} {'wake1':>6s} {'tail0':>6s} {'tail1':>6s} {'gapBefore':>9s}  (medians, us)")
tot=dict(wall=0,i0=0,i1=0,gap=0)
for n in order:
    if n not in stats: continue
    d=stats[n]; m=lambda k: st.median([x[k] for x in d])
    w=m('wall');i0=st.median([x['wall']-x['b0'] for x in d]);i1=st.median([x['wall']-x['b1'] for x in d])
    print(f"{n:12s} {m('cnt'):5.0f} {w:7.0f} {m('b0'):7.0f} {m('b1'):7.0f} {i0:6.0f} {i1:6.0f} {m('wake'):6.0f} {m('tail0'):6.0f} {m('tail1'):6.0f} {m('gap'):9.0f}")
    tot['wall']+=w;tot['i0']+=i0;tot['i1']+=i1;tot['gap']+=m('gap')
print('sum of job walls',round(tot['wall']),'idle0',round(tot['i0']),'idle1',round(tot['i1']),'serial gaps',round(tot['gap']))
print('frame (cull start..resolve end) median',round(st.median([x['wall'] for x in stats['_frame']])), 'min', round(min(x['wall'] for x in stats['_frame'])))
