"""Datasets written from decoded captures (Parquet)."""
