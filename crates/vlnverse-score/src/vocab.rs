//! The instruction vocabulary: `DIR/vocab.txt`, one token per line, line number = token id.
//!
//! Id 0 is `<pad>`, 1 is `<unk>`; the rest are the tokens of the dataset's training
//! instructions, most frequent first (ties alphabetical), so the file is deterministic.
//! Tokens are lower-case words and single punctuation marks ([`tokenize`]).

use std::collections::BTreeMap;
use std::path::Path;

use crate::episode::Episode;
use crate::error::{DataError, Result};

/// File name of the vocabulary in a dataset folder.
pub const VOCAB_FILE: &str = "vocab.txt";
/// Padding token (id 0).
pub const PAD: &str = "<pad>";
/// Unknown-word token (id 1).
pub const UNK: &str = "<unk>";

/// Split an instruction into lower-case words (letters, digits, apostrophes, hyphens inside a
/// word) and single punctuation marks; whitespace separates.
pub fn tokenize(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    for c in text.chars() {
        if c.is_alphanumeric() || ((c == '\'' || c == '-') && !word.is_empty()) {
            word.extend(c.to_lowercase());
        } else {
            if !word.is_empty() {
                out.push(std::mem::take(&mut word));
            }
            if !c.is_whitespace() {
                out.push(c.to_string());
            }
        }
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

/// A token list with ids.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Vocab {
    tokens: Vec<String>,
    ids: BTreeMap<String, u32>,
}

impl Vocab {
    /// A vocabulary from tokens in id order (`<pad>`, `<unk>` first).
    pub fn from_tokens(tokens: Vec<String>) -> Self {
        let ids = tokens
            .iter()
            .enumerate()
            .map(|(i, t)| (t.clone(), i as u32))
            .collect();
        Vocab { tokens, ids }
    }

    /// The vocabulary of the instructions (and sub-instructions) of `episodes`.
    pub fn build<'a>(episodes: impl IntoIterator<Item = &'a Episode>) -> Self {
        let mut counts: BTreeMap<String, u64> = BTreeMap::new();
        for ep in episodes {
            let ins = &ep.instruction;
            let texts = std::iter::once(&ins.instruction_text).chain(&ins.sub_instructions);
            for t in texts {
                for tok in tokenize(t) {
                    *counts.entry(tok).or_default() += 1;
                }
            }
        }
        let mut by_count: Vec<(String, u64)> = counts.into_iter().collect();
        by_count.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        let tokens = [PAD.to_string(), UNK.to_string()]
            .into_iter()
            .chain(by_count.into_iter().map(|(t, _)| t))
            .collect();
        Vocab::from_tokens(tokens)
    }

    /// Read `vocab.txt`.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| DataError::io(path, e))?;
        let tokens: Vec<String> = text.lines().map(str::to_string).collect();
        if tokens.len() < 2 || tokens[0] != PAD || tokens[1] != UNK {
            return Err(DataError::invalid(
                format!("{}: lines 1-2", path.display()),
                tokens
                    .iter()
                    .take(2)
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", "),
                format!("a vocabulary starts with {PAD} and {UNK}"),
            ));
        }
        Ok(Vocab::from_tokens(tokens))
    }

    /// The file's text: one token per line.
    pub fn to_text(&self) -> String {
        let mut s = self.tokens.join("\n");
        s.push('\n');
        s
    }

    /// Tokens in id order.
    pub fn tokens(&self) -> &[String] {
        &self.tokens
    }

    /// Number of tokens (ids are `0..len`).
    pub fn len(&self) -> usize {
        self.tokens.len()
    }

    /// Whether the vocabulary has no tokens.
    pub fn is_empty(&self) -> bool {
        self.tokens.is_empty()
    }

    /// Token ids of `text`, cut or padded (with 0) to `len`; unknown words are 1.
    pub fn encode(&self, text: &str, len: usize) -> Vec<u32> {
        let mut ids: Vec<u32> = tokenize(text)
            .iter()
            .map(|t| self.ids.get(t).copied().unwrap_or(1))
            .take(len)
            .collect();
        ids.resize(len, 0);
        ids
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_are_lower_case_words_and_punctuation() {
        assert_eq!(
            tokenize("Walk past the TV-stand, then stop. Don't"),
            ["walk", "past", "the", "tv-stand", ",", "then", "stop", ".", "don't"]
        );
    }

    #[test]
    fn ids_follow_frequency_and_unknown_words_are_one() {
        let mut a = Episode::default();
        a.instruction.instruction_text = "go left, go".into();
        let v = Vocab::build([&a]);
        assert_eq!(v.tokens(), ["<pad>", "<unk>", "go", ",", "left"]);
        assert_eq!(v.encode("Go right", 4), [2, 1, 0, 0]);
        assert_eq!(Vocab::from_tokens(v.tokens().to_vec()), v);
    }
}
