"""Plane geometry of parts: rings in mm, arcs fitted to them, circles, bores and offsets.

Imports nothing from gearcad but its errors: every stage above may use it.
"""
