"""A user's own blisk sector from a mesh file: reader, checks, model and import report
(docs/imported.md)."""
