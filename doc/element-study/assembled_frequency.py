#!/usr/bin/python3
"""Assembled highest frequency vs the element estimate min h/c on a field frame.
eig.py name frame K G rho0 : elastic stiffness with bulk K and shear G on the frame's
geometry (plain tet; the averaged elements are softer volumetrically), lumped masses
m_e/4 from rho0 V0; prints 2/omega_max, min_e h/c, and their ratio."""
import sys; import numpy as np, h5py, scipy.sparse as sp, scipy.sparse.linalg as sl
name, frame, K, G, rho0 = sys.argv[1], sys.argv[2], *map(float, sys.argv[3:6])
form = sys.argv[6] if len(sys.argv) > 6 else 'plain'; beta = float(sys.argv[7]) if len(sys.argv) > 7 else 0.0
f = h5py.File(f'out_{name}/{name}.h5', 'r')
conn = f['mesh/connectivity'][:]; x0 = f['mesh/x0'][:]
nid = f['mesh/node_id'][:]
if conn.max() >= len(x0):
    idx = np.full(nid.max()+1, -1); idx[nid] = np.arange(len(nid)); conn = idx[conn]
frames = sorted(f['steps'].keys()); fr = frames[int(frame)]
X = f['steps'][fr]['coordinates'][:]
def geom(P):
    d1 = P[:,1]-P[:,0]; d2 = P[:,2]-P[:,0]; d3 = P[:,3]-P[:,0]
    g2 = np.cross(d2,d3); g3 = np.cross(d3,d1); g4 = np.cross(d1,d2)
    six = np.einsum('ij,ij->i', d1, g2)
    g = np.stack([-(g2+g3+g4), g2, g3, g4], axis=1)/six[:,None,None]
    return six/6.0, g
V0, _ = geom(x0[conn]); V, g = geom(X[conn])
me = rho0*V0
mn = np.zeros(len(X)); np.add.at(mn, conn.ravel(), np.repeat(me/4, 4))
lam = K - 2*G/3
ne = len(conn)
# K_e[a i, b j] = V (lam g_ai g_bj + G (g_aj g_bi + d_ij g_a.g_b))
ke = (-2*G/3*np.einsum('eai,ebj->eaibj', g, g) + G*np.einsum('eaj,ebi->eaibj', g, g)
      + G*np.einsum('eak,ebk,ij->eaibj', g, g, np.eye(3)))*V[:,None,None,None,None]
dof = (3*conn[:,:,None] + np.arange(3)[None,None,:]).reshape(ne, 12)
rows = np.repeat(dof, 12, axis=1).ravel(); cols = np.tile(dof, (1, 12)).ravel()
Kg = sp.coo_matrix((ke.reshape(ne, 144).ravel(), (rows, cols)), shape=(3*len(X),)*2).tocsr()
# volumetric part: K V0e (dJ*/dx)(dJ*/dx)^T, J* = J_e (plain), Jbar_e (nodal), (1-b)Jbar + b J_e (stabilised)
nn = len(X)
B = sp.coo_matrix(((V[:,None]*g.reshape(ne,12)).ravel(), (np.repeat(np.arange(ne),12), dof.ravel())), shape=(ne,3*nn)).tocsr()
Je = sp.diags(1/V0) @ B
if form != 'plain':
    inc = sp.coo_matrix((np.ones(4*ne), (conn.ravel(), np.repeat(np.arange(ne),4))), shape=(nn,ne)).tocsr()
    V0a = 0.25*(inc @ V0)
    Ja = sp.diags(0.25/V0a) @ inc @ B          # dJ_a/dx
    Jb = 0.25*(inc.T @ Ja)                      # dJbar_e/dx
    Jg = (1-beta)*Jb + beta*Je
else:
    Jg = Je
Kg = Kg + Jg.T @ sp.diags(K*V0) @ Jg
mi = 1/np.sqrt(np.repeat(mn, 3))
A = sp.diags(mi) @ Kg @ sp.diags(mi)
gersh = np.asarray(abs(A).sum(axis=1)).ravel().max()
w2 = sl.eigsh(A, k=1, which='LA', return_eigenvectors=False, tol=1e-6)[0]
dt_sys = 2/np.sqrt(w2)
h = 1/np.max(np.linalg.norm(g, axis=2), axis=1)
c = np.sqrt((K + 4*G/3)*V/me)
dte = h/c
# single-element bound: each element alone with m_e/4 per node
print(f"{name} [{form} {beta}] frame {fr}: elements {ne} nodes {len(X)}: assembled 2/omega_max {dt_sys:.3e} s; "
      f"min_e h/c {dte.min():.3e} s (median {np.median(dte):.3e}); ratio {dt_sys/dte.min():.2f}; "
      f"V/V0 min {np.min(V/V0):.3f}; Gershgorin 2/sqrt(rowsum) {2/np.sqrt(gersh):.3e} s = {2/np.sqrt(gersh)/dte.min():.2f} h/c")
