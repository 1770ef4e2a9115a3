"""Linear algebra the reference scripts share (standard library only)."""


def total(values):
    """The sum of values, added left to right (Python 3.12's sum() compensates its rounding, which
    would change the references' last digits from one Python to the next)."""
    s = 0.0
    for v in values:
        s += v
    return s


def gauss(matrix, rhs):
    """The solution of matrix x = rhs by Gaussian elimination with partial pivoting."""
    m = [row[:] + [b] for row, b in zip(matrix, rhs)]
    size = len(m)
    for col in range(size):
        best = max(range(col, size), key=lambda r: abs(m[r][col]))
        m[col], m[best] = m[best], m[col]
        for r in range(col + 1, size):
            f = m[r][col] / m[col][col]
            for c in range(col, size + 1):
                m[r][c] -= f * m[col][c]
    x = [0.0] * size
    for r in range(size - 1, -1, -1):
        x[r] = (m[r][size] - total(m[r][c] * x[c] for c in range(r + 1, size))) / m[r][r]
    return x
