"""Every lobe model of the catalog (facet models --json), alone at its defaults, through
tests/tools/hlsl_check.sh: the HLSL pixel shader and the --library, each through glslang's
HLSL front end.   hlsl_models.py FACET CHECK_SCRIPT OUTDIR"""
import json
import os
import subprocess
import sys


def main():
    facet, check, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    catalog = json.loads(subprocess.run([facet, "models", "--json"], check=True, capture_output=True, text=True).stdout)
    failed, done = [], 0
    for section in ("diffuse", "specular"):
        for model in catalog["sections"][section]:
            lobe = {"model": model["name"]}
            for p in model["parameters"]:
                if p["required"]:
                    lobe[p["name"]] = p["default"]
            path = os.path.join(out, f"model_{model['name']}.json")
            with open(path, "w") as f:
                json.dump({"name": f"model_{model['name']}", section: lobe}, f)
            r = subprocess.run(["sh", check, facet, path, out], capture_output=True, text=True)
            done += 1
            if r.returncode != 0:
                failed.append(model["name"])
                print(f"FAIL {section} {model['name']}:\n{r.stdout}{r.stderr}")
    print(f"{done} models, {2 * done} HLSL files through glslangValidator -D -V -S frag -e main; {len(failed)} failed")
    return 1 if failed or done == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
