"""What every writer shares: number formatting, mesh paths, CLI flags, output staging and the target contract."""
