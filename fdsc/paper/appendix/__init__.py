"""The book's appendices that compute: the reproduction report (``reproduction_report``: the
record as table rows and counts). The appendix on the printed bounds uses
:mod:`fdsc.paper.reproduced.printed_bounds`, the environment page
:mod:`fdsc.paper.shared.environment`.

A module here imports the library, :mod:`fdsc.paper.shared`, the parts and the record
(:mod:`fdsc.paper.record`).
"""

__all__ = []  # used through its modules
