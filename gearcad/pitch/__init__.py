"""Pitch curves: polar curves, conjugate synthesis, closure and kinematics (numpy/scipy only)."""
