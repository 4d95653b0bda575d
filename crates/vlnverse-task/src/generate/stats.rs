//! Dataset statistics (placeholder until the plots land).
