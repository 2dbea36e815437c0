"""Material sources: one module per library graph, each with build() -> SbsGraph and SAMPLE_RANGES."""
