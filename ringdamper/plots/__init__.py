"""Figures of the campaign (matplotlib, Agg backend)."""
import matplotlib

matplotlib.use("Agg")
