"""Screen cheap, prove the few: the front's rows re-designed at the full stage.

A sweep at the pitch or teeth stage is a screen: those stages cannot see every failure (the teeth
stage's report lists what it is blind to in ``stage_blind``: interference and play where a pitch
curve is concave, as a required motion's often is).  ``confirm="full"`` re-designs each front row
at the full stage, through the sweep's own workers, and marks it: ``confirmed`` true where the
full design is made, passes every check (``ok``) and still meets the constraints; false with the
reason in ``confirm_refusal`` — the refusal, the failing finding codes (``failed: interference,
play``) or the constraint it misses at the full stage.  The front is then taken again among the
rows not refuted, and any row new to it is confirmed in turn (at most :data:`ROUNDS` rounds), so
that ``pareto`` marks only proven rows; rows never re-designed have ``confirmed`` empty.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ProfileError

__all__ = ["CONFIRMS", "ROUNDS", "check_confirm", "confirm_front"]

CONFIRMS = ("full",)
ROUNDS = 5
"""Rounds of confirming at most: a front whose every row fails five times over is left unproven
(``pareto`` false everywhere, each refuted row saying why)."""


def check_confirm(confirm: Any, stage: str) -> None:
    if confirm is None:
        return
    if confirm not in CONFIRMS:
        raise ProfileError(f"confirm = {confirm!r}: must be one of {', '.join(CONFIRMS)}")
    if stage == confirm:
        raise ProfileError(f"--confirm {confirm}: the sweep is already at the {stage} stage; confirm a cheaper one")


def _plain(value: Any) -> Any:
    return value.item() if isinstance(value, np.generic) else value


def _verdict(row: dict, conditions) -> str | None:
    """None if the full design proves the row, else why not (one line)."""
    from .front import feasible

    if row.get("refusal") is not None:
        return f"refused: {row['refusal']}"
    failed = row.get("failures") or ""
    if failed or row.get("ok") is False:
        return f"failed: {', '.join(failed.split()) or 'a check'}"
    import pandas as pd

    table = pd.DataFrame([row])
    for condition in conditions:
        if condition[0] not in table or not feasible(table, [condition])[0]:
            return f"misses {condition} at the full stage (there: {row.get(condition[0])!r})"
    return None


def confirm_front(table, data: dict, name: str, conditions, run, *, workers, client, scheduler_timeout, progress):
    """The table with ``confirmed`` and ``confirm_refusal`` columns and ``pareto`` taken again
    among the rows not refuted (see the module)."""
    import pandas as pd

    from .front import pareto

    minimise, maximise = table.attrs.get("minimise", []), table.attrs.get("maximise", [])
    inputs = table.attrs.get("inputs", [])
    confirmed = pd.array([pd.NA] * len(table), dtype="boolean")
    reasons: list[Any] = [None] * len(table)
    ok = table["feasible"].to_numpy(bool).copy()
    values = [
        pd.to_numeric(table[k], errors="coerce").to_numpy(float) * (1 if k in minimise else -1)
        for k in [*minimise, *maximise]
    ]
    front = table["pareto"].to_numpy(bool).copy()
    for _ in range(ROUNDS):
        todo = [i for i in np.flatnonzero(front) if confirmed[i] is pd.NA]
        if not todo:
            break
        overrides = [{c[4:]: _plain(table[c].iloc[i]) for c in inputs} for i in todo]
        rows = run(data, name, "full", overrides, workers=workers, client=client,
                   scheduler_timeout=scheduler_timeout, progress=progress)  # fmt: skip
        for i, row in zip(todo, rows):
            why = _verdict(row, conditions)
            confirmed[i] = why is None
            reasons[i] = why
            ok[i] &= why is None
        front = pareto(np.column_stack(values), ok) if values else np.zeros(len(table), dtype=bool)
    proven = confirmed.fillna(False).to_numpy(bool)
    out = table.copy()
    out["pareto"] = front & proven
    at = list(out.columns).index("pareto") + 1
    out.insert(at, "confirmed", confirmed)
    out.insert(at + 1, "confirm_refusal", pd.array(reasons, dtype="object"))
    out.attrs.update(table.attrs, confirm="full")
    return out
