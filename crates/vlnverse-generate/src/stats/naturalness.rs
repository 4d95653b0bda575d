//! How close the instructions' wording is to human navigation language: a word-bigram model
//! fitted on human instructions (one per line), the perplexity it gives each task's
//! instructions against the perplexity it gives held-out human instructions, and the share of
//! words the human text never uses.
//!
//! - **Tokens**: lower-cased; a word is a run of letters, digits and apostrophes (curly ones
//!   read as `'`), apostrophes at its ends trimmed; all other punctuation is dropped. A sentence
//!   ends at `.`, `!` or `?` followed by a space or the end of the line (so "3.4" stays in one
//!   sentence); every sentence is one sequence `<s> w1 .. wn </s>`, and `</s>` is predicted
//!   (counted in the perplexity), `<s>` is not.
//! - **Model**: interpolated absolute discounting (Ney, Essen and Kneser 1994):
//!   `P(w|v) = max(c(v,w) - D, 0) / c(v) + D * N1+(v .) / c(v) * P1(w)`, with the unigram
//!   `P1(w) = c(w) / N` over the predicted tokens and `D = n1 / (n1 + 2 n2)` from the counts of
//!   bigram types seen once and twice.
//! - **Unknown words**: the words seen only once in the fitted text form one class, `<unk>`,
//!   that is counted like a word when fitting (so it has unigram and bigram counts of its own),
//!   and a word of that class or a word never seen gets `P(<unk>|v) / K`, K being the number of
//!   words in the class: an unseen word costs what a word seen once costs. The distribution is
//!   proper over the fitted vocabulary, so every perplexity is finite and every text is scored
//!   by the same model.
//! - **Out of vocabulary**: a word absent from the fitted text (seen-once words are not OOV).

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use serde::Serialize;
use vlnverse_score::dataset::{read_split, split_path};
use vlnverse_score::episode::{Split, Task};
use vlnverse_score::{DataError, Result};

/// Every `HOLDOUT_EVERY`-th line of a reference file (the 10th, 20th, ...) is held out when no
/// separate held-out file is given.
const HOLDOUT_EVERY: usize = 10;
/// How many of the most frequent OOV words a group lists.
const TOP_OOV: usize = 20;

const BOS: u32 = 0;
const EOS: u32 = 1;
const UNK: u32 = 2;

/// Sentences of `text` as lists of lower-case words (see the module notes).
fn sentences(text: &str) -> Vec<Vec<String>> {
    let lower = text.to_lowercase().replace(['\u{2019}', '\u{2018}'], "'");
    let chars: Vec<char> = lower.chars().collect();
    let mut out = Vec::new();
    let mut sentence = Vec::new();
    let mut word = String::new();
    let flush = |word: &mut String, sentence: &mut Vec<String>| {
        let w = word.trim_matches('\'');
        if !w.is_empty() {
            sentence.push(w.to_string());
        }
        word.clear();
    };
    for (i, &c) in chars.iter().enumerate() {
        if c.is_alphanumeric() || c == '\'' {
            word.push(c);
            continue;
        }
        flush(&mut word, &mut sentence);
        let ends =
            matches!(c, '.' | '!' | '?') && chars.get(i + 1).is_none_or(|n| n.is_whitespace());
        if ends && !sentence.is_empty() {
            out.push(std::mem::take(&mut sentence));
        }
    }
    flush(&mut word, &mut sentence);
    if !sentence.is_empty() {
        out.push(sentence);
    }
    out
}

/// A fitted word-bigram model (see the module notes).
#[derive(Debug)]
pub(crate) struct BigramModel {
    /// Every word of the fitted text (including seen-once words): the OOV test.
    seen: HashMap<String, usize>,
    /// Model ids of the words seen at least twice (0, 1, 2 are `<s>`, `</s>`, `<unk>`).
    ids: HashMap<String, u32>,
    /// Words in the `<unk>` class.
    unk_class: usize,
    bigrams: HashMap<(u32, u32), u32>,
    /// Per context: tokens that follow it, and distinct tokens that follow it.
    context: Vec<(u64, u64)>,
    unigram: Vec<u64>,
    predicted: u64,
    discount: f64,
}

impl BigramModel {
    /// Fit on `lines` (one instruction each); `discount` overrides the estimated D.
    pub(crate) fn fit<'a>(
        lines: impl IntoIterator<Item = &'a str>,
        discount: Option<f64>,
    ) -> std::result::Result<BigramModel, String> {
        let text: Vec<Vec<Vec<String>>> = lines.into_iter().map(sentences).collect();
        let mut seen: HashMap<String, usize> = HashMap::new();
        for w in text.iter().flatten().flatten() {
            *seen.entry(w.clone()).or_default() += 1;
        }
        if seen.is_empty() {
            return Err("holds no words".into());
        }
        // Ids in sorted word order, so the model does not depend on hash order.
        let mut frequent: Vec<&String> = seen
            .iter()
            .filter(|(_, &c)| c >= 2)
            .map(|(w, _)| w)
            .collect();
        frequent.sort();
        let ids: HashMap<String, u32> = frequent
            .iter()
            .enumerate()
            .map(|(i, w)| ((*w).clone(), i as u32 + 3))
            .collect();
        let unk_class = seen.len() - ids.len();
        if unk_class == 0 {
            return Err(
                "has no word that occurs only once, so the unknown-word class cannot be fitted \
                 (a reference of human instructions always has some)"
                    .into(),
            );
        }
        let n_ids = ids.len() + 3;
        let mut bigrams: HashMap<(u32, u32), u32> = HashMap::new();
        let mut unigram = vec![0u64; n_ids];
        let mut predicted = 0u64;
        for sentence in text.iter().flatten() {
            let mut prev = BOS;
            let tokens = sentence
                .iter()
                .map(|w| ids.get(w).copied().unwrap_or(UNK))
                .chain(std::iter::once(EOS));
            for t in tokens {
                *bigrams.entry((prev, t)).or_default() += 1;
                unigram[t as usize] += 1;
                predicted += 1;
                prev = t;
            }
        }
        let mut context = vec![(0u64, 0u64); n_ids];
        let (mut n1, mut n2) = (0u64, 0u64);
        for (&(v, _), &c) in &bigrams {
            context[v as usize].0 += u64::from(c);
            context[v as usize].1 += 1;
            match c {
                1 => n1 += 1,
                2 => n2 += 1,
                _ => {}
            }
        }
        let discount = match discount {
            Some(d) => d,
            None if n1 + 2 * n2 > 0 => n1 as f64 / (n1 + 2 * n2) as f64,
            None => 0.5,
        };
        Ok(BigramModel {
            seen,
            ids,
            unk_class,
            bigrams,
            context,
            unigram,
            predicted,
            discount,
        })
    }

    /// `P(t | v)` for model tokens (the `<unk>` class as a whole).
    fn prob(&self, v: u32, t: u32) -> f64 {
        let p1 = self.unigram[t as usize] as f64 / self.predicted as f64;
        let (cv, followers) = self.context[v as usize];
        if cv == 0 {
            return p1;
        }
        let c = self.bigrams.get(&(v, t)).copied().unwrap_or(0) as f64;
        let cv = cv as f64;
        (c - self.discount).max(0.0) / cv + self.discount * followers as f64 / cv * p1
    }

    /// Score texts: total natural-log probability, predicted tokens, words, OOV words.
    fn score<'a>(&self, texts: impl IntoIterator<Item = &'a str>) -> Scored {
        let mut s = Scored::default();
        for text in texts {
            s.texts += 1;
            for sentence in sentences(text) {
                let mut prev = BOS;
                for w in &sentence {
                    s.words += 1;
                    if !self.seen.contains_key(w) {
                        *s.oov.entry(w.clone()).or_default() += 1;
                    }
                    let t = self.ids.get(w).copied().unwrap_or(UNK);
                    let mut p = self.prob(prev, t);
                    if t == UNK {
                        p /= self.unk_class as f64;
                    }
                    s.log_prob += p.ln();
                    s.tokens += 1;
                    prev = t;
                }
                s.log_prob += self.prob(prev, EOS).ln();
                s.tokens += 1;
            }
        }
        s
    }
}

/// What scoring a group of texts sums up.
#[derive(Debug, Default)]
struct Scored {
    texts: usize,
    words: u64,
    tokens: u64,
    log_prob: f64,
    oov: BTreeMap<String, u64>,
}

impl Scored {
    fn perplexity(&self) -> f64 {
        if self.tokens == 0 {
            return f64::NAN;
        }
        (-self.log_prob / self.tokens as f64).exp()
    }
}

/// The naturalness figures of one group of instructions (a task, a task's style, or the
/// held-out human text).
#[derive(Clone, Debug, Serialize)]
pub struct GroupNaturalness {
    /// Task name (`human` for the held-out reference).
    pub task: String,
    /// Coarse style name, or `all`.
    pub style: String,
    /// Instructions scored.
    pub instructions: usize,
    /// Word tokens scored.
    pub words: u64,
    /// Perplexity per predicted token (words and sentence ends).
    pub perplexity: f64,
    /// Perplexity over the held-out human perplexity.
    pub ratio: f64,
    /// Share (0..1) of word tokens that never occur in the fitted reference.
    pub oov_share: f64,
    /// The most frequent of those words, with their counts.
    pub top_oov: Vec<(String, u64)>,
}

/// A dataset's instructions measured against human instructions (`xtask stats --reference`).
#[derive(Clone, Debug, Serialize)]
pub struct Naturalness {
    /// The reference file.
    pub reference: String,
    /// Where the held-out human text came from.
    pub heldout: String,
    /// Instructions the model was fitted on.
    pub fit_instructions: usize,
    /// Word tokens the model was fitted on.
    pub fit_words: u64,
    /// Distinct words of the fitted text (the OOV test's vocabulary).
    pub fit_vocabulary: usize,
    /// Of those, the words seen only once (the unknown-word class).
    pub unknown_class: usize,
    /// The absolute discount D.
    pub discount: f64,
    /// The held-out human instructions.
    pub human: GroupNaturalness,
    /// Per task, then per coarse style.
    pub groups: Vec<GroupNaturalness>,
}

/// Non-empty lines of a reference file; a missing, unreadable or empty file is an error naming
/// it.
fn read_lines(path: &Path) -> Result<Vec<String>> {
    let text = std::fs::read_to_string(path).map_err(|e| DataError::io(path, e))?;
    let lines: Vec<String> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(str::to_string)
        .collect();
    if lines.is_empty() {
        return Err(DataError::parse(
            path,
            "whole file",
            "holds no instructions (expected one human instruction per line)",
        ));
    }
    Ok(lines)
}

/// Fit the model on `reference` (without every tenth line, which is the held-out text, unless
/// `heldout` names a file of its own) and score every task's instructions in `dir` (all splits
/// present), per task and per coarse style.
pub fn naturalness(dir: &Path, reference: &Path, heldout: Option<&Path>) -> Result<Naturalness> {
    let lines = read_lines(reference)?;
    let held_lines = heldout.map(read_lines).transpose()?;
    let (fit, held, held_from): (Vec<&str>, Vec<&str>, String) = match &held_lines {
        Some(h) => (
            lines.iter().map(String::as_str).collect(),
            h.iter().map(String::as_str).collect(),
            heldout.unwrap_or(reference).display().to_string(),
        ),
        None => {
            let (mut fit, mut held) = (Vec::new(), Vec::new());
            for (i, l) in lines.iter().enumerate() {
                if i % HOLDOUT_EVERY == HOLDOUT_EVERY - 1 {
                    held.push(l.as_str());
                } else {
                    fit.push(l.as_str());
                }
            }
            if held.is_empty() {
                return Err(DataError::parse(
                    reference,
                    "whole file",
                    format!(
                        "{} lines: every {HOLDOUT_EVERY}th line is held out, so at least \
                         {HOLDOUT_EVERY} are needed (or give a held-out file with --heldout)",
                        lines.len()
                    ),
                ));
            }
            (
                fit,
                held,
                format!("every {HOLDOUT_EVERY}th line of {}", reference.display()),
            )
        }
    };
    let model = BigramModel::fit(fit.iter().copied(), None)
        .map_err(|m| DataError::parse(reference, "whole file", m))?;
    let texts = instructions_by_group(dir)?;
    let human_scored = model.score(held.iter().copied());
    let human_ppl = human_scored.perplexity();
    let group = |task: &str, style: &str, s: &Scored| {
        let mut top: Vec<(String, u64)> = s.oov.iter().map(|(w, &c)| (w.clone(), c)).collect();
        top.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        top.truncate(TOP_OOV);
        let oov: u64 = s.oov.values().sum();
        GroupNaturalness {
            task: task.into(),
            style: style.into(),
            instructions: s.texts,
            words: s.words,
            perplexity: s.perplexity(),
            ratio: s.perplexity() / human_ppl,
            oov_share: oov as f64 / s.words.max(1) as f64,
            top_oov: top,
        }
    };
    let human = group("human", "all", &human_scored);
    let mut groups = Vec::new();
    for ((task, style), list) in &texts {
        let s = model.score(list.iter().map(String::as_str));
        groups.push(group(task, style, &s));
    }
    Ok(Naturalness {
        reference: reference.display().to_string(),
        heldout: held_from,
        fit_instructions: fit.len(),
        fit_words: model.seen.values().map(|&c| c as u64).sum(),
        fit_vocabulary: model.seen.len(),
        unknown_class: model.unk_class,
        discount: model.discount,
        human,
        groups,
    })
}

/// Instruction texts per (task, style), tasks in [`Task::ALL`] order with `all` first; a task
/// with styles also gets one group per style.
fn instructions_by_group(dir: &Path) -> Result<Vec<((String, String), Vec<String>)>> {
    let mut out = Vec::new();
    for task in Task::ALL {
        let mut all = Vec::new();
        let mut styles: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for split in Split::ALL {
            if !split_path(dir, task, split).is_file() {
                continue;
            }
            for ep in read_split(dir, task, split)? {
                let text = ep.instruction.instruction_text;
                if let Some(s) = ep.instruction.style {
                    styles
                        .entry(s.name().to_string())
                        .or_default()
                        .push(text.clone());
                }
                all.push(text);
            }
        }
        if all.is_empty() {
            continue;
        }
        out.push(((task.name().to_string(), "all".to_string()), all));
        for (style, list) in styles {
            out.push(((task.name().to_string(), style), list));
        }
    }
    Ok(out)
}

impl Naturalness {
    /// The figures as a markdown section (a table and the frequent OOV words per group).
    pub fn markdown(&self) -> String {
        let mut md = String::from("\n## Naturalness against human instructions\n\n");
        md.push_str(&format!(
            "Word-bigram model with absolute discounting (D = {:.3}) interpolated with the \
             unigram, fitted on {} instructions of `{}` ({} words, {} distinct, {} of them seen \
             once: the unknown-word class); held out: {}.\n\n",
            self.discount,
            self.fit_instructions,
            self.reference,
            self.fit_words,
            self.fit_vocabulary,
            self.unknown_class,
            self.heldout
        ));
        md.push_str(
            "| text | instructions | words | perplexity | ratio to held-out human | OOV share |\n\
             |---|---|---|---|---|---|\n",
        );
        let label = |g: &GroupNaturalness| match (g.task.as_str(), g.style.as_str()) {
            ("human", _) => "held-out human".to_string(),
            (t, "all") => t.to_string(),
            (t, s) => format!("{t}, {s}"),
        };
        for g in std::iter::once(&self.human).chain(&self.groups) {
            md.push_str(&format!(
                "| {} | {} | {} | {:.1} | {:.2}x | {:.2}% |\n",
                label(g),
                g.instructions,
                g.words,
                g.perplexity,
                g.ratio,
                100.0 * g.oov_share
            ));
        }
        md.push_str("\nMost frequent OOV words (count):\n\n");
        for g in std::iter::once(&self.human).chain(&self.groups) {
            let words: Vec<String> = g
                .top_oov
                .iter()
                .map(|(w, c)| format!("{w} ({c})"))
                .collect();
            let words = if words.is_empty() {
                "none".to_string()
            } else {
                words.join(", ")
            };
            md.push_str(&format!("- {}: {words}\n", label(g)));
        }
        md
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_are_lower_case_words_in_sentences() {
        assert_eq!(
            sentences("Walk past the Sofa. Stop!  Then 3.4 metres, it's there’s"),
            vec![
                vec!["walk", "past", "the", "sofa"],
                vec!["stop"],
                vec!["then", "3", "4", "metres", "it's", "there's"],
            ]
        );
        assert_eq!(sentences(" 'quoted' -- "), vec![vec!["quoted"]]);
        assert!(sentences("...").is_empty());
    }

    /// Reference: "go left" x2, "go right" x1, "turn left" x1 (one sentence each).
    /// Words: go 3, left 3, right 1, turn 1 -> vocabulary {go, left}, <unk> = {right, turn}
    /// (K = 2). Token streams: <s> go left </s> (x2), <s> go <unk> </s>, <s> <unk> left </s>.
    /// Bigram counts: (<s>,go) 3, (<s>,unk) 1, (go,left) 2, (go,unk) 1, (left,</s>) 3,
    /// (unk,</s>) 1, (unk,left) 1. Predicted tokens N = 12: go 3, left 3, unk 2, </s> 4.
    /// With D = 0.5:
    ///   P(go|<s>)   = (3-0.5)/4 + 0.5*2/4 * 3/12 = 0.625 + 0.0625   = 0.6875
    ///   P(left|go)  = (2-0.5)/3 + 0.5*2/3 * 3/12 = 0.5 + 1/12       = 7/12
    ///   P(</s>|left) = (3-0.5)/3 + 0.5*1/3 * 4/12 = 5/6 + 1/18      = 8/9
    ///   P(unk|left) = 0 + 0.5*1/3 * 2/12 = 1/36, over K = 2        = 1/72
    ///   P(</s>|unk) = (1-0.5)/2 + 0.5*2/2 * 4/12 = 0.25 + 1/6       = 5/12
    /// "go left" -> 0.6875 * 7/12 * 8/9 over 3 tokens;
    /// "go left zebra" -> 0.6875 * 7/12 * 1/72 * 5/12 over 4 tokens.
    #[test]
    fn perplexity_matches_a_hand_computation() {
        let reference = ["go left", "go right", "go left", "turn left"];
        let m = BigramModel::fit(reference, Some(0.5)).unwrap();
        assert_eq!(m.unk_class, 2);
        let expect = |probs: &[f64]| {
            (-(probs.iter().map(|p| p.ln()).sum::<f64>()) / probs.len() as f64).exp()
        };
        let s = m.score(["go left"]);
        assert_eq!((s.words, s.tokens), (2, 3));
        let want = expect(&[0.6875, 7.0 / 12.0, 8.0 / 9.0]);
        assert!(
            (s.perplexity() - want).abs() < 1e-12,
            "{} vs {want}",
            s.perplexity()
        );
        let s = m.score(["go left zebra"]);
        let want = expect(&[0.6875, 7.0 / 12.0, 1.0 / 72.0, 5.0 / 12.0]);
        assert!(
            (s.perplexity() - want).abs() < 1e-12,
            "{} vs {want}",
            s.perplexity()
        );
        // "zebra" is OOV; "right" is a seen-once word: scored as <unk> but not OOV.
        assert_eq!(s.oov.get("zebra"), Some(&1));
        let s = m.score(["go right"]);
        assert!(s.oov.is_empty());
        // Bigram types: 7, of which 4 seen once and 1 twice -> D = 4 / (4 + 2).
        let est = BigramModel::fit(reference, None).unwrap();
        assert!((est.discount - 4.0 / 6.0).abs() < 1e-12, "{}", est.discount);
    }

    #[test]
    fn the_model_is_a_distribution_over_its_tokens() {
        let reference = [
            "walk past the sofa and stop",
            "turn left at the hallway. walk on",
            "go through the door and stop by the bed",
            "walk straight past the table",
        ];
        let m = BigramModel::fit(reference, None).unwrap();
        let n = m.unigram.len() as u32;
        for v in (0..n).filter(|&v| v != EOS) {
            let total: f64 = (1..n).map(|t| m.prob(v, t)).sum();
            assert!((total - 1.0).abs() < 1e-9, "context {v}: {total}");
        }
    }

    /// A dataset whose every instruction is "Walk to the goal." against a reference that lacks
    /// "goal": one word in four is OOV, and the held-out part is every tenth line.
    #[test]
    fn a_dataset_is_scored_per_task_against_the_held_out_lines() {
        let d = tempfile::tempdir().unwrap();
        let eps = vlnverse_testkit::datasets::make_dataset(d.path(), Task::Fine, 1, 3, 5);
        let reference = d.path().join("human.txt");
        let lines: Vec<String> = (0..20)
            .map(|i| format!("walk to the door {i} and stop. turn left at the sofa"))
            .collect();
        std::fs::write(&reference, lines.join("\n")).unwrap();
        let n = naturalness(d.path(), &reference, None).unwrap();
        assert_eq!((n.fit_instructions, n.human.instructions), (18, 2));
        assert_eq!(n.groups.len(), 1);
        let fine = &n.groups[0];
        assert_eq!((fine.task.as_str(), fine.style.as_str()), ("fine", "all"));
        assert_eq!(fine.instructions, eps.len());
        assert_eq!(fine.words, 4 * eps.len() as u64);
        assert!((fine.oov_share - 0.25).abs() < 1e-12, "{}", fine.oov_share);
        assert_eq!(fine.top_oov, vec![("goal".to_string(), eps.len() as u64)]);
        assert!(fine.perplexity.is_finite() && fine.ratio > 1.0, "{fine:?}");
        assert!(
            n.markdown().contains("| fine | 3 | 12 |"),
            "{}",
            n.markdown()
        );
    }

    #[test]
    fn a_reference_without_rare_words_is_refused() {
        let err = BigramModel::fit(["go left", "go left"], None).unwrap_err();
        assert!(err.contains("only once"), "{err}");
        assert!(BigramModel::fit(["", "..."], None)
            .unwrap_err()
            .contains("no words"));
    }
}
