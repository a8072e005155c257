"""Plants, closed loops and the aircraft benchmark of Sec. IV.

The plant is paper eq. (10)::

    dx/dt = A x + B1 d + B2 u,     z = C x + D1 d + D2 u,

and state feedback ``u = K x`` gives the closed loop
``(A + B2 K, B1, C + D2 K, D1)``. (The paper's switched closed loop prints
``C + B2 K``; the dimensions force ``C + D2 K``.)
"""

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._validation import as_matrix
from .bands import band_from_spec

__all__ = ["LTISystem", "Plant", "aircraft", "paper_data", "paper_gains", "paper_bands",
           "data_dir"]


@dataclass(frozen=True)
class LTISystem:
    """A continuous-time LTI system ``dx/dt = A x + B d, z = C x + D d``.

    Parameters
    ----------
    A : (n, n) array_like
    B : (n, m) array_like
    C : (p, n) array_like
    D : (p, m) array_like

    Examples
    --------
    >>> sys = LTISystem([[-1.0]], [[1.0]], [[1.0]], [[0.0]])
    >>> sys.n_states, sys.is_hurwitz()
    (1, True)
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray

    def __post_init__(self):
        A = as_matrix("A", self.A, square=True)
        n = A.shape[0]
        B = as_matrix("B", self.B, (n, None))
        C = as_matrix("C", self.C, (None, n))
        D = as_matrix("D", self.D, (C.shape[0], B.shape[1]))
        for name, val in zip("ABCD", (A, B, C, D), strict=True):
            object.__setattr__(self, name, val)

    @property
    def n_states(self):
        """Number of states n."""
        return self.A.shape[0]

    @property
    def n_inputs(self):
        """Number of disturbance inputs m."""
        return self.B.shape[1]

    @property
    def n_outputs(self):
        """Number of regulated outputs p."""
        return self.C.shape[0]

    def poles(self):
        """Eigenvalues of A, sorted by real part (most negative first)."""
        ev = np.linalg.eigvals(self.A)
        return ev[np.argsort(ev.real)]

    def is_hurwitz(self, margin=0.0):
        """True if every eigenvalue of A has real part < ``-margin``."""
        return bool(np.all(np.linalg.eigvals(self.A).real < -margin))


@dataclass(frozen=True)
class Plant:
    """The open-loop plant (8): ``dx/dt = A x + B1 d + B2 u``, ``z = C x + D1 d + D2 u``.

    Parameters
    ----------
    A : (n, n) array_like
    B1 : (n, m_d) array_like
        Disturbance input matrix.
    B2 : (n, m_u) array_like
        Control input matrix.
    C : (p, n) array_like
    D1 : (p, m_d) array_like
    D2 : (p, m_u) array_like
    names : dict, optional
        Names of states, inputs and outputs (for plots).

    Examples
    --------
    >>> p = aircraft()
    >>> cl = p.closed_loop(np.zeros((2, 2)))
    >>> cl.A.shape, cl.C.shape
    ((2, 2), (3, 2))
    """

    A: np.ndarray
    B1: np.ndarray
    B2: np.ndarray
    C: np.ndarray
    D1: np.ndarray
    D2: np.ndarray
    names: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        A = as_matrix("A", self.A, square=True)
        n = A.shape[0]
        B1 = as_matrix("B1", self.B1, (n, None))
        B2 = as_matrix("B2", self.B2, (n, None))
        C = as_matrix("C", self.C, (None, n))
        D1 = as_matrix("D1", self.D1, (C.shape[0], B1.shape[1]))
        D2 = as_matrix("D2", self.D2, (C.shape[0], B2.shape[1]))
        for name, val in (("A", A), ("B1", B1), ("B2", B2), ("C", C), ("D1", D1), ("D2", D2)):
            object.__setattr__(self, name, val)

    @property
    def n_states(self):
        """Number of states n."""
        return self.A.shape[0]

    @property
    def n_controls(self):
        """Number of control inputs."""
        return self.B2.shape[1]

    def closed_loop(self, K):
        """Closed loop under ``u = K x``: ``(A + B2 K, B1, C + D2 K, D1)``.

        Parameters
        ----------
        K : (m_u, n) array_like
            State-feedback gain.

        Returns
        -------
        LTISystem
            The map from d to z.

        Raises
        ------
        DimensionError
            If K is not of shape ``(m_u, n)``.
        """
        K = as_matrix("K", K, (self.n_controls, self.n_states))
        return LTISystem(self.A + self.B2 @ K, self.B1, self.C + self.D2 @ K, self.D1)


def data_dir():
    """Folder ``data/`` of the repository (beside the ``fdsc`` package).

    Raises
    ------
    FileNotFoundError
        If fdsc is not run from a checkout of the repository.
    """
    path = Path(__file__).resolve().parent.parent / "data"
    if not path.is_dir():
        raise FileNotFoundError(f"fdsc expects the paper's data in {path}; install fdsc from a "
                                "checkout of the repository (pip install -e .)")
    return path


def paper_data(name):
    """Load ``data/<name>.json`` (a dict of ``{"value": ..., "source": ...}`` entries).

    Examples
    --------
    >>> paper_data("controllers")["K_f1"]["bound"]
    0.3443
    """
    path = data_dir() / f"{name}.json"
    if not path.is_file():
        available = sorted(p.stem for p in data_dir().glob("*.json"))
        raise FileNotFoundError(f"name: no data file {path.name}; available: {available}")
    with path.open(encoding="utf-8") as fh:
        return json.load(fh)


def aircraft():
    """The longitudinal aircraft model of Sec. IV (two states, two controls, one disturbance).

    Returns
    -------
    Plant
    """
    d = paper_data("aircraft")
    names = {k: d[k]["value"] for k in ("state_names", "input_names", "output_names")}
    return Plant(*(np.array(d[k]["value"]) for k in ("A", "B1", "B2", "C", "D1", "D2")),
                 names=names)


def paper_gains():
    """The printed gains ``{"K_f1": K, "K_f2": K, "K_f3": K, "K_e": K}`` (arrays (2, 2))."""
    d = paper_data("controllers")
    return {k: np.array(v["value"]) for k, v in d.items() if k.startswith("K_")}


def paper_bands():
    """The paper's bands ``{"LF": Ω_1, "MF": Ω_2, "HF": Ω_3, "EF": Ω_e}`` as :class:`Band`."""
    specs = paper_data("aircraft")["bands"]["value"]
    bands = {}
    for spec in specs.values():
        b = band_from_spec(spec)
        bands[b.kind] = b
    bands["EF"] = band_from_spec({"kind": "EF"})
    return bands
