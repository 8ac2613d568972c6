"""Bodies that turn and oscillate while touching three rollers (seed 003)."""
