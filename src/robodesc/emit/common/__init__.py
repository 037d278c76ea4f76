"""What every writer shares: number formatting, mesh paths, atomic files and the target contract."""
