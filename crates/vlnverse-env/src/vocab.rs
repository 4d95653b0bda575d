//! The fixed semantic vocabulary: object classes and room types.
//!
//! Class ids are stable: they are written into semantic images and dataset files, so new classes
//! are only ever appended. Id 0 is reserved for "nothing" in semantic images, so the first class
//! has id 1. `docs/formats.md` lists the table.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

macro_rules! vocabulary {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $( $variant:ident = ($id:expr, $text:expr, $kind:ident) ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        $vis enum $name {
            $(
                #[doc = concat!("`", $text, "`")]
                $variant,
            )*
        }

        impl $name {
            /// Every member, in id order.
            pub const ALL: &'static [$name] = &[$($name::$variant),*];

            /// Stable numeric id (written into semantic images; 0 means "none").
            pub fn id(self) -> u16 {
                match self { $($name::$variant => $id),* }
            }

            /// Snake-case name used in files and instructions' metadata.
            pub fn name(self) -> &'static str {
                match self { $($name::$variant => $text),* }
            }

            /// Look a member up by its stable id.
            pub fn from_id(id: u16) -> Option<Self> {
                match id { $($id => Some($name::$variant),)* _ => None }
            }

            /// Look a member up by its snake-case name.
            pub fn from_name(name: &str) -> Option<Self> {
                match name { $($text => Some($name::$variant),)* _ => None }
            }

            #[allow(dead_code)] // used by SemanticClass only
            fn kind_of(self) -> ClassKind {
                match self { $($name::$variant => ClassKind::$kind),* }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl FromStr for $name {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                Self::from_name(s).ok_or_else(|| format!("unknown {} `{s}`", stringify!($name)))
            }
        }

        impl Serialize for $name {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> Deserialize<'de> for $name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let s = String::deserialize(d)?;
                Self::from_name(&s).ok_or_else(|| serde::de::Error::custom(format!(
                    "unknown {} `{s}`", stringify!($name)
                )))
            }
        }
    };
}

/// What a class is: building structure, furniture standing on the floor, or a small object
/// that stands on furniture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClassKind {
    /// Walls, floor, ceiling, door frames, windows, railings: never a landmark or a target.
    Structure,
    /// Floor-standing furniture and appliances.
    Furniture,
    /// Objects small enough to stand on furniture (`X on Y` relations).
    Small,
    /// Anything the importer could not label.
    Unknown,
}

vocabulary! {
    /// Semantic class of a scene object (the fixed vocabulary, 120+ classes).
    pub enum SemanticClass {
        Wall = (1, "wall", Structure),
        Floor = (2, "floor", Structure),
        Ceiling = (3, "ceiling", Structure),
        DoorFrame = (4, "door_frame", Structure),
        Window = (5, "window", Structure),
        Bed = (6, "bed", Furniture),
        Nightstand = (7, "nightstand", Furniture),
        Wardrobe = (8, "wardrobe", Furniture),
        Dresser = (9, "dresser", Furniture),
        Toilet = (10, "toilet", Furniture),
        Sink = (11, "sink", Furniture),
        Bathtub = (12, "bathtub", Furniture),
        Shower = (13, "shower", Furniture),
        Mirror = (14, "mirror", Furniture),
        Fridge = (15, "fridge", Furniture),
        Counter = (16, "counter", Furniture),
        Stove = (17, "stove", Furniture),
        Dishwasher = (18, "dishwasher", Furniture),
        KitchenCabinet = (19, "kitchen_cabinet", Furniture),
        Sofa = (20, "sofa", Furniture),
        Armchair = (21, "armchair", Furniture),
        Tv = (22, "tv", Furniture),
        TvStand = (23, "tv_stand", Furniture),
        CoffeeTable = (24, "coffee_table", Furniture),
        DiningTable = (25, "dining_table", Furniture),
        Chair = (26, "chair", Furniture),
        Desk = (27, "desk", Furniture),
        OfficeChair = (28, "office_chair", Furniture),
        Bookshelf = (29, "bookshelf", Furniture),
        PottedPlant = (30, "potted_plant", Furniture),
        FloorLamp = (31, "floor_lamp", Furniture),
        Rug = (32, "rug", Furniture),
        Cabinet = (33, "cabinet", Furniture),
        SideTable = (34, "side_table", Furniture),
        ShoeRack = (35, "shoe_rack", Furniture),
        CoatRack = (36, "coat_rack", Furniture),
        WashingMachine = (37, "washing_machine", Furniture),
        Piano = (38, "piano", Furniture),
        Bench = (39, "bench", Furniture),
        Stool = (40, "stool", Furniture),
        TrashCan = (41, "trash_can", Furniture),
        Cup = (42, "cup", Small),
        Mug = (43, "mug", Small),
        Book = (44, "book", Small),
        Laptop = (45, "laptop", Small),
        Vase = (46, "vase", Small),
        Bowl = (47, "bowl", Small),
        Bottle = (48, "bottle", Small),
        Clock = (49, "clock", Small),
        TableLamp = (50, "table_lamp", Small),
        SmallPlant = (51, "small_plant", Small),
        Monitor = (52, "monitor", Small),
        Keyboard = (53, "keyboard", Small),
        Remote = (54, "remote", Small),
        Pillow = (55, "pillow", Small),
        Toaster = (56, "toaster", Small),
        Kettle = (57, "kettle", Small),
        Microwave = (58, "microwave", Small),
        Candle = (59, "candle", Small),
        PictureFrame = (60, "picture_frame", Small),
        Towel = (61, "towel", Small),
        SoapDispenser = (62, "soap_dispenser", Small),
        Plate = (63, "plate", Small),
        Unknown = (64, "unknown", Unknown),
        Door = (65, "door", Furniture),
        FruitBowl = (66, "fruit_bowl", Small),
        Teapot = (67, "teapot", Small),
        Pot = (68, "pot", Small),
        Pan = (69, "pan", Small),
        CuttingBoard = (70, "cutting_board", Small),
        CoffeeMachine = (71, "coffee_machine", Small),
        Blender = (72, "blender", Small),
        DishRack = (73, "dish_rack", Small),
        TissueBox = (74, "tissue_box", Small),
        Basket = (75, "basket", Small),
        Speaker = (76, "speaker", Small),
        Phone = (77, "phone", Small),
        Tablet = (78, "tablet", Small),
        Printer = (79, "printer", Small),
        PenHolder = (80, "pen_holder", Small),
        Globe = (81, "globe", Small),
        BoardGame = (82, "board_game", Small),
        Toy = (83, "toy", Small),
        JewelryBox = (84, "jewelry_box", Small),
        ToiletPaper = (85, "toilet_paper", Small),
        Shampoo = (86, "shampoo", Small),
        ToothbrushHolder = (87, "toothbrush_holder", Small),
        Hairdryer = (88, "hairdryer", Small),
        Magazine = (89, "magazine", Small),
        Headphones = (90, "headphones", Small),
        Shoes = (91, "shoes", Furniture),
        Slippers = (92, "slippers", Furniture),
        LaundryBasket = (93, "laundry_basket", Furniture),
        Box = (94, "box", Furniture),
        Backpack = (95, "backpack", Furniture),
        UmbrellaStand = (96, "umbrella_stand", Furniture),
        DogBed = (97, "dog_bed", Furniture),
        YogaMat = (98, "yoga_mat", Furniture),
        Dumbbells = (99, "dumbbells", Furniture),
        Ottoman = (100, "ottoman", Furniture),
        BeanBag = (101, "bean_bag", Furniture),
        Chest = (102, "chest", Furniture),
        Vanity = (103, "vanity", Furniture),
        FilingCabinet = (104, "filing_cabinet", Furniture),
        WallShelf = (105, "wall_shelf", Furniture),
        TowelRack = (106, "towel_rack", Furniture),
        Curtain = (107, "curtain", Furniture),
        Radiator = (108, "radiator", Furniture),
        Fan = (109, "fan", Furniture),
        Heater = (110, "heater", Furniture),
        Fireplace = (111, "fireplace", Furniture),
        Aquarium = (112, "aquarium", Furniture),
        Treadmill = (113, "treadmill", Furniture),
        ExerciseBike = (114, "exercise_bike", Furniture),
        Bicycle = (115, "bicycle", Furniture),
        IroningBoard = (116, "ironing_board", Furniture),
        DryingRack = (117, "drying_rack", Furniture),
        Crib = (118, "crib", Furniture),
        HighChair = (119, "high_chair", Furniture),
        PatioChair = (120, "patio_chair", Furniture),
        PatioTable = (121, "patio_table", Furniture),
        Planter = (122, "planter", Furniture),
        ClothesRail = (123, "clothes_rail", Furniture),
        ShelvingUnit = (124, "shelving_unit", Furniture),
        Stairs = (125, "stairs", Furniture),
        Railing = (126, "railing", Structure),
        Recliner = (127, "recliner", Furniture),
        RockingChair = (128, "rocking_chair", Furniture),
        PoolTable = (129, "pool_table", Furniture),
        PingPongTable = (130, "ping_pong_table", Furniture),
        FoosballTable = (131, "foosball_table", Furniture),
        GrandfatherClock = (132, "grandfather_clock", Furniture),
        Guitar = (133, "guitar", Furniture),
        DrumKit = (134, "drum_kit", Furniture),
        Statue = (135, "statue", Furniture),
        FireExtinguisher = (136, "fire_extinguisher", Furniture),
        Dryer = (137, "dryer", Furniture),
        Easel = (138, "easel", Furniture),
        Birdcage = (139, "birdcage", Furniture),
        Grill = (140, "grill", Furniture),
        KitchenIsland = (141, "kitchen_island", Furniture),
        ConsoleTable = (142, "console_table", Furniture),
        ChinaCabinet = (143, "china_cabinet", Furniture),
        Ladder = (144, "ladder", Furniture),
        Column = (145, "column", Furniture),
        Chandelier = (146, "chandelier", Furniture),
        MassageTable = (147, "massage_table", Furniture),
        Hammock = (148, "hammock", Furniture),
        ChaiseLounge = (149, "chaise_lounge", Furniture),
        Cactus = (150, "cactus", Furniture),
        Urn = (151, "urn", Furniture),
        Lounger = (152, "lounger", Furniture),
        WeightBench = (153, "weight_bench", Furniture),
        PunchingBag = (154, "punching_bag", Furniture),
        ProjectorScreen = (155, "projector_screen", Furniture),
        Projector = (156, "projector", Small),
        PopcornMachine = (157, "popcorn_machine", Furniture),
        Jar = (158, "jar", Small),
        WineRack = (159, "wine_rack", Furniture),
        Lockers = (160, "lockers", Furniture),
        ArcadeMachine = (161, "arcade_machine", Furniture),
        Car = (162, "car", Furniture),
        Workbench = (163, "workbench", Furniture),
        ChristmasTree = (164, "christmas_tree", Furniture),
        WallSconce = (165, "wall_sconce", Furniture),
        Poster = (166, "poster", Furniture),
        PorchSwing = (167, "porch_swing", Furniture),
        Doormat = (168, "doormat", Furniture),
        Runner = (169, "runner", Furniture),
        GrandPiano = (170, "grand_piano", Furniture),
        HotTub = (171, "hot_tub", Furniture),
        Fountain = (172, "fountain", Furniture),
        WaterCooler = (173, "water_cooler", Furniture),
        Tapestry = (174, "tapestry", Furniture),
        RoomDivider = (175, "room_divider", Furniture),
        Wreath = (176, "wreath", Furniture),
        DeerHead = (177, "deer_head", Furniture),
        Flag = (178, "flag", Furniture),
        Elliptical = (179, "elliptical", Furniture),
        RowingMachine = (180, "rowing_machine", Furniture),
        Bar = (181, "bar", Furniture),
        Dollhouse = (182, "dollhouse", Furniture),
        AirHockeyTable = (183, "air_hockey_table", Furniture),
        PinballMachine = (184, "pinball_machine", Furniture),
        Dartboard = (185, "dartboard", Furniture),
        Barrel = (186, "barrel", Furniture),
        BunkBed = (187, "bunk_bed", Furniture),
        RockingHorse = (188, "rocking_horse", Furniture),
        CatTree = (189, "cat_tree", Furniture),
        VacuumCleaner = (190, "vacuum_cleaner", Furniture),
        LawnMower = (191, "lawn_mower", Furniture),
        Kayak = (192, "kayak", Furniture),
        Telescope = (193, "telescope", Furniture),
        Jukebox = (194, "jukebox", Furniture),
        Sectional = (195, "sectional", Furniture),
        Buffet = (196, "buffet", Furniture),
        CeilingFan = (197, "ceiling_fan", Furniture),
        WaterHeater = (198, "water_heater", Furniture),
        MiniFridge = (199, "mini_fridge", Furniture),
        TeddyBear = (200, "teddy_bear", Furniture),
        Bust = (201, "bust", Furniture),
        Saxophone = (202, "saxophone", Furniture),
        BasketballHoop = (203, "basketball_hoop", Furniture),
        Whiteboard = (204, "whiteboard", Furniture),
        BulletinBoard = (205, "bulletin_board", Furniture),
        ChessTable = (206, "chess_table", Furniture),
        Candelabra = (207, "candelabra", Furniture),
        ExerciseBall = (208, "exercise_ball", Furniture),
        Sword = (209, "sword", Furniture),
        Rocks = (210, "rocks", Furniture),
        LightSwitch = (211, "light_switch", Furniture),
        Outlet = (212, "outlet", Furniture),
        Thermostat = (213, "thermostat", Furniture),
        AirVent = (214, "air_vent", Furniture),
        SmokeDetector = (215, "smoke_detector", Furniture),
        Calendar = (216, "calendar", Furniture),
        AirConditioner = (217, "air_conditioner", Furniture),
        RangeHood = (218, "range_hood", Furniture),
        Futon = (219, "futon", Furniture),
        Daybed = (220, "daybed", Furniture),
        TrophyCase = (221, "trophy_case", Furniture),
        Amplifier = (222, "amplifier", Furniture),
        Microphone = (223, "microphone", Furniture),
        Violin = (224, "violin", Furniture),
        Toolbox = (225, "toolbox", Furniture),
        Wheelbarrow = (226, "wheelbarrow", Furniture),
        Shovel = (227, "shovel", Furniture),
        GardenHose = (228, "garden_hose", Furniture),
        Suitcase = (229, "suitcase", Furniture),
        MopBucket = (230, "mop_bucket", Furniture),
        Broom = (231, "broom", Furniture),
        BathroomScale = (232, "bathroom_scale", Furniture),
        Firewood = (233, "firewood", Furniture),
        SpiceRack = (234, "spice_rack", Furniture),
        SewingMachine = (235, "sewing_machine", Furniture),
        Typewriter = (236, "typewriter", Furniture),
        RecordPlayer = (237, "record_player", Furniture),
        Radio = (238, "radio", Furniture),
        KnifeBlock = (239, "knife_block", Furniture),
    }
}

impl SemanticClass {
    /// Whether the class is building structure (wall, floor, ceiling, door frame, window).
    pub fn is_structure(self) -> bool {
        self.kind_of() == ClassKind::Structure
    }

    /// Structure, furniture, small object or unknown.
    pub fn kind(self) -> ClassKind {
        self.kind_of()
    }

    /// Words used in text ("coffee table" for `coffee_table`).
    pub fn words(self) -> String {
        self.name().replace('_', " ")
    }
}

vocabulary! {
    /// Kind of room in a home.
    pub enum RoomType {
        LivingRoom = (1, "living_room", Structure),
        Kitchen = (2, "kitchen", Structure),
        DiningRoom = (3, "dining_room", Structure),
        Bedroom = (4, "bedroom", Structure),
        Bathroom = (5, "bathroom", Structure),
        Hallway = (6, "hallway", Structure),
        Office = (7, "office", Structure),
        LaundryRoom = (8, "laundry_room", Structure),
        Closet = (9, "closet", Structure),
        Gym = (10, "gym", Structure),
        Room = (11, "room", Structure),
        EntranceHall = (12, "entrance_hall", Structure),
        Balcony = (13, "balcony", Structure),
        Pantry = (14, "pantry", Structure),
        HomeTheater = (15, "home_theater", Structure),
        Library = (16, "library", Structure),
        Garage = (17, "garage", Structure),
        Porch = (18, "porch", Structure),
        Sauna = (19, "sauna", Structure),
        Spa = (20, "spa", Structure),
        WineCellar = (21, "wine_cellar", Structure),
        Playroom = (22, "playroom", Structure),
        MudRoom = (23, "mud_room", Structure),
        Workshop = (24, "workshop", Structure),
    }
}

impl RoomType {
    /// Words used in text ("living room" for `living_room`).
    pub fn words(self) -> String {
        self.name().replace('_', " ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_and_names_round_trip_and_are_unique() {
        let mut ids = std::collections::HashSet::new();
        for &c in SemanticClass::ALL {
            assert!(ids.insert(c.id()), "duplicate id {}", c.id());
            assert_eq!(SemanticClass::from_id(c.id()), Some(c));
            assert_eq!(SemanticClass::from_name(c.name()), Some(c));
        }
        let objects = SemanticClass::ALL
            .iter()
            .filter(|c| matches!(c.kind(), ClassKind::Furniture | ClassKind::Small))
            .count();
        assert!(
            objects >= 100,
            "vocabulary has only {objects} object classes"
        );
    }

    #[test]
    fn serde_uses_snake_case_names() {
        let json = serde_json::to_string(&SemanticClass::CoffeeTable).unwrap();
        assert_eq!(json, "\"coffee_table\"");
        let back: SemanticClass = serde_json::from_str(&json).unwrap();
        assert_eq!(back, SemanticClass::CoffeeTable);
        assert!(serde_json::from_str::<SemanticClass>("\"spaceship\"").is_err());
    }
}
