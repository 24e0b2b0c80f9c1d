"""Figures of the campaign and of its studies (matplotlib, Agg backend), drawn from the data the
stages and studies return; they import the layers below them, never the studies."""
import matplotlib

matplotlib.use("Agg")
