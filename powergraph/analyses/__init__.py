"""Analyses beyond power flow: backlash (seeds/002), cycloid fluctuation (seeds/003),
volume (seeds/004), sweeps and closed-form formulas."""
