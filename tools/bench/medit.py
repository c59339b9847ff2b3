"""An ASCII Medit .mesh/.sol reader for the benchmark scripts (tools/bench/gmsh.sh): 2D or 3D."""


def tokens(path):
    for line in open(path):
        yield from line.split('#')[0].split()


def medit(path):
    """The sections of a .mesh or .sol file: 'v' vertices (coordinates only), 't' triangles, 'k'
    tetrahedra (indices from 0, references dropped), 'm' the solution at vertices (3 entries per vertex
    in 2D, 6 in 3D, in Medit's order)."""
    t = tokens(path)
    sec, dim = {}, 2
    for w in t:
        if w == 'Dimension':
            dim = int(next(t))
        elif w == 'Vertices':
            n = int(next(t))
            sec['v'] = [tuple(float(next(t)) for _ in range(dim + 1))[:dim] for _ in range(n)]
        elif w in ('Edges', 'Triangles', 'Tetrahedra'):
            n, k = int(next(t)), {'Edges': 2, 'Triangles': 3, 'Tetrahedra': 4}[w]
            rows = [tuple(int(next(t)) - 1 for _ in range(k + 1))[:k] for _ in range(n)]
            sec[{'Edges': 'e', 'Triangles': 't', 'Tetrahedra': 'k'}[w]] = rows
        elif w in ('Corners', 'RequiredVertices', 'Ridges'):
            [next(t) for _ in range(int(next(t)))]
        elif w == 'SolAtVertices':
            n = int(next(t)); next(t); next(t)
            sec['m'] = [tuple(float(next(t)) for _ in range(3 if dim == 2 else 6)) for _ in range(n)]
        elif w == 'End':
            break
    return sec
