"""Generated code of the derived model: H, C, G, Q, inverse and forward dynamics (docs/code.md)."""
