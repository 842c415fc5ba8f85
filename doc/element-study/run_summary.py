# run_summary.py NAME [RHO0]: one line per run (cycles, steps, energy error, element V/V0 min,
# L and footprint by postproc/taylor.py, ns) from NAME.log and out_NAME/; /usr/bin/python3.
import sys, csv, re, json, subprocess
sys.path.insert(0,'/work/wt-elem/postproc')
import numpy as np, h5py, taylor
name=sys.argv[1]; rho0=float(sys.argv[2]) if len(sys.argv)>2 else 8960.0
rows=list(csv.DictReader(open(f'out_{name}/{name}_history.csv')))
log=open(f'{name}.log').read()
dts=[float(r['dt']) for r in rows[1:-1] if float(r['dt'])>0]
ms=list(re.finditer(r'cycle +(\d+) +t +(\S+) s +dt +(\S+) s',log))
for m in ms[:-1]: dts.append(float(m.group(3)))
meandt=float(rows[-1]['time'])/max(1,int(rows[-1]['cycle']))
m=re.search(r'done: (\d+) cycles.*?energy error (\S+),.*?\((\S+) ns per element-cycle\)',log)
cyc,err,ns=(m.group(1),m.group(2),m.group(3)) if m else ('FAIL','','')
f=h5py.File(f'out_{name}/{name}.h5','r')
steps=sorted(f['steps'].keys())
jmin=min(float((rho0/f['steps'][s]['density'][:]).min()) for s in steps)
x=f['steps'][steps[-1]]['coordinates'][:]
mm=taylor.measure(x,axis=2,wall=0.0,center=(0.0,0.0))
first=0.7*float(re.search(r'stable step +(\S+) s',log).group(1))
coll=re.findall(r'time-step collapse: stable step (\S+) s',log)
print(f"{name}: cycles {cyc} dt_first {first:.3e} dt_min_printed {min(dts):.3e} ratio {min(dts)/first:.3g} mean_dt {meandt:.3e} energy_err {err} elJmin {jmin:.3f} Lf {mm['length_m']*1e3:.3f} Dfoot {mm['footprint_diameter_m']*1e3:.3f} ns {ns} warnings {len(coll)} t_end {float(rows[-1]['time']):.3e}")
conn=f['mesh/connectivity'][:]
# node ids -> rows
nid=f['mesh/node_id'][:]
idx=np.full(nid.max()+1,-1); idx[nid]=np.arange(len(nid))
c=idx[conn] if conn.max()>=len(nid) or conn.min()>0 and False else None
worst=1e9
for s in steps[1:]:
    X=f['steps'][s]['coordinates'][:]
    cc=conn if conn.max()<len(X) else idx[conn]
    P=X[cc]  # (ne,4,3)
    d1=P[:,1]-P[:,0]; d2=P[:,2]-P[:,0]; d3=P[:,3]-P[:,0]
    g=[np.cross(d2,d3),np.cross(d3,d1),np.cross(d1,d2)]
    six=np.einsum('ij,ij->i',d1,g[0])
    g1=-(g[0]+g[1]+g[2])
    gm=np.max(np.stack([np.linalg.norm(v,axis=1) for v in g+[g1]]),axis=0)
    h=np.abs(six)/gm
    worst=min(worst,h.min()/np.median(h))
print(f"   h_min/h_median worst over frames {worst:.3f} (frames {len(steps)})")
