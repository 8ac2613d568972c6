"""Other mechanisms around gears: trains on a carrier, a wheel driven through an inclined rack."""
