"""Full 360-degree model assembled from N rotated copies of the sector (test oracle for cyclic symmetry).

Sector j's matrices are R_j K R_j^T (node-wise rotation by j 2 pi / N about Z); its right-cut nodes are
sector j+1's left-cut nodes, so the global numbering merges them; the bore is clamped.
"""
import numpy as np
import scipy.sparse as sp


def _rotation(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def full_node_numbering(model):
    """(N, n_nodes) global node index of every sector node."""
    n_sec, n_nodes = model.n_sectors, len(model.nodes)
    is_right = np.zeros(n_nodes, dtype=bool)
    is_right[model.right_nodes] = True
    own = np.flatnonzero(~is_right)
    local = np.full(n_nodes, -1)
    local[own] = np.arange(len(own))
    index = np.empty((n_sec, n_nodes), dtype=int)
    for j in range(n_sec):
        index[j, own] = j * len(own) + local[own]
    for j in range(n_sec):
        index[j, model.right_nodes] = index[(j + 1) % n_sec, model.left_nodes]
    return index, n_sec * len(own)


def assemble_full(model, sector_matrices):
    """Global matrices of the annulus and the free (not clamped) DoFs."""
    index, n_full = full_node_numbering(model)
    out = []
    for A in sector_matrices:
        A = sp.coo_matrix(A)
        blocks = []
        for j in range(model.n_sectors):
            R = sp.block_diag([_rotation(j * model.sector_angle)] * len(model.nodes), format="csr")
            Aj = sp.coo_matrix(R @ A @ R.T)
            dof = 3 * index[j][:, None] + np.arange(3)
            dof = dof.ravel()
            blocks.append(sp.coo_matrix((Aj.data, (dof[Aj.row], dof[Aj.col])), shape=(3 * n_full,) * 2))
        out.append(sum(blocks).tocsr())
    fixed = np.unique((3 * index[:, model.fixed_nodes][..., None] + np.arange(3)).ravel())
    free = np.setdiff1d(np.arange(3 * n_full), fixed)
    return out, free
