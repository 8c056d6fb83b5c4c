//! One definition for the run-time choices chosen by name (approximator, rule, experiment):
//! the enum with its serde and clap names, `ALL`, `name()`, `Display` and name lookup, so the
//! command line, run ids and `summary.json` can never disagree about a spelling.

/// Defines a `Copy` enum whose variants are named by string literals:
///
/// ```ignore
/// named_choices! {
///     /// Doc.
///     pub enum Colour {
///         /// Doc.
///         Red => "red",
///     }
/// }
/// ```
///
/// The enum derives serde and `clap::ValueEnum` with exactly these names and gets
/// `ALL` (declaration order), `name()`, `from_name()`, `names()` (for error messages) and
/// `Display`. Each type writes its own `FromStr` with its own error type.
macro_rules! named_choices {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $( $(#[$vmeta:meta])* $variant:ident => $text:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(
            Debug,
            Clone,
            Copy,
            PartialEq,
            Eq,
            Hash,
            PartialOrd,
            Ord,
            serde::Serialize,
            serde::Deserialize,
        )]
        #[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
        pub enum $name {
            $(
                $(#[$vmeta])*
                #[serde(rename = $text)]
                #[cfg_attr(feature = "cli", value(name = $text))]
                $variant,
            )+
        }

        impl $name {
            /// Every choice, in declaration (table) order.
            pub const ALL: [$name; [$($text),+].len()] = [$($name::$variant),+];

            /// The name used on the command line, in run ids and in `summary.json`.
            pub fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }

            /// The choice called `name`, if any.
            pub fn from_name(name: &str) -> Option<Self> {
                Self::ALL.into_iter().find(|k| k.name() == name)
            }

            /// Every name, for messages: `"a, b or c"`.
            pub fn names() -> String {
                let all: Vec<&str> = Self::ALL.iter().map(|k| k.name()).collect();
                match all.split_last() {
                    Some((last, rest)) if !rest.is_empty() => {
                        format!("{} or {last}", rest.join(", "))
                    }
                    _ => all.join(""),
                }
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

pub(crate) use named_choices;

#[cfg(test)]
mod tests {
    named_choices! {
        /// A test choice.
        pub enum Colour {
            /// Red.
            Red => "red",
            /// Dark blue.
            DarkBlue => "dark-blue",
            /// Green.
            Green => "green",
        }
    }

    #[test]
    #[cfg(feature = "cli")]
    fn names_agree_across_serde_clap_display_and_lookup() {
        use clap::ValueEnum;
        assert_eq!(Colour::ALL, [Colour::Red, Colour::DarkBlue, Colour::Green]);
        for c in Colour::ALL {
            assert_eq!(Colour::from_name(c.name()), Some(c));
            assert_eq!(c.to_string(), c.name());
            assert_eq!(
                serde_json::to_string(&c).unwrap(),
                format!("\"{}\"", c.name())
            );
            let p = c.to_possible_value().unwrap();
            assert_eq!(p.get_name(), c.name());
        }
        assert_eq!(Colour::from_name("blue"), None);
        assert_eq!(Colour::names(), "red, dark-blue or green");
        assert!(serde_json::from_str::<Colour>("\"DarkBlue\"").is_err());
    }
}
