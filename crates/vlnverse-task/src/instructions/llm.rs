//! Optional LLM stage (placeholder, filled in below).
