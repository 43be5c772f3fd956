"""Engine: geometry, cylinder ends, model assembly, integration, ideal card."""
