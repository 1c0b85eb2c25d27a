"""The models every bench runs: the CAD files of tests/data (their sources
and licences in tests/data/SOURCES.md), the same folder the tests read, so
there is one list. SIZEMESH_MODELS_DIR may point at another folder."""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
DIR = os.environ.get("SIZEMESH_MODELS_DIR", os.path.join(os.path.dirname(HERE), "tests", "data"))
CAD = (".step", ".stp", ".iges", ".igs", ".brep")
MODELS = sorted(f for f in os.listdir(DIR) if f.lower().endswith(CAD))

# The aircraft the union is developed against; they do not all give one closed
# surface yet (the same list as union_corpus() in tests/test_models.h).
UNION_CORPUS = ["transport_wbnp_openvsp.stp", "tbw_sugar_openvsp.stp", "pegasus_openvsp.stp",
                "wing_blunt_te_openvsp.stp", "wing_blunt_te2_openvsp.stp", "c172_wing_pygeo.igs",
                "b777_onepiece_openvsp.stp", "b777_nosplit_openvsp.stp", "f16_vsp311_openvsp.stp"]
