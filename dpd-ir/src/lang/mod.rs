//! The scheme language: grammar, parser, expansion to a flattened program.
