"""Teeth: a generating rack rolled without slip along each pitch curve (numpy, scipy, shapely)."""
