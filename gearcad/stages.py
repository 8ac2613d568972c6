"""The stages a design may stop at, in order: ``full`` (parts, proof, everything a build writes)
for every mechanism; the earlier ones for a mechanism whose registry entry has a ``stages`` hook
(a gear pair: ``pitch``, the pitch curves and their checks; ``teeth``, the teeth by closed form)."""

STAGES: tuple[str, ...] = ("pitch", "teeth", "full")
